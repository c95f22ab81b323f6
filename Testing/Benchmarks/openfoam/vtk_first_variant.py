"""The first variant on a plain VTK pipeline, for the design-of-experiments benchmark
(run-doe-benchmark.sh): the same case, regions and settings as doe_benchmark.py's set-up (the
hull a Handle translated by 0.1 m, inlet and outlet Fixed, the other planes Slip), in Debian's
python3 with ParaView's VTK modules and the filters' Python wrapping beside the plugin, without
ParaView's server manager (what a VTK C++ pipeline pays too). Timed from the process's start to
the variant written (a linked case in OUT_FOLDER/variant), as doe_benchmark.py's first variant.
Prints one JSON line (VTKFIRST {...}).
Usage: python3 vtk_first_variant.py PLUGIN_FOLDER CASE.foam OUT_FOLDER"""
import os
import json
import sys
import time

start = time.time()
plugin_folder, foam, out = sys.argv[1:4]
sys.path.insert(0, plugin_folder)
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet  # noqa: E402
from vtkmodules.vtkIOGeometry import vtkOpenFOAMReader  # noqa: E402
import mlsdeform_wrapping.MLSDeformFilters as filters  # noqa: E402
import mlsdeform_wrapping.MLSDeformReaders as readers  # noqa: E402

ROLES = [('hull', filters.vtkConstraintRegion.Handle), ('inlet', filters.vtkConstraintRegion.Fixed),
         ('outlet', filters.vtkConstraintRegion.Fixed)] + [(p, filters.vtkConstraintRegion.Slip) for p in ('sideYmin', 'sideYmax', 'bottom', 'top')]
result = {'startup_s': time.time() - start}
reader = vtkOpenFOAMReader()
reader.SetFileName(foam)
reader.SetDecomposePolyhedra(0)   # checkMesh's own cells, as doe_benchmark.py
reader.SetCacheMesh(0)
reader.UpdateInformation()
for i in range(reader.GetNumberOfPatchArrays()):
    name = reader.GetPatchArrayName(i)
    reader.SetPatchArrayStatus(name, 1 if name == 'internalMesh' or name.replace('patch/', '') in dict(ROLES) else 0)
reader.Update()
mesh = reader.GetOutput()
result['read_s'] = time.time() - start - result['startup_s']
boundary = mesh.GetBlock(1)
patches = {boundary.GetMetaData(i).Get(vtkMultiBlockDataSet.NAME()): boundary.GetBlock(i) for i in range(boundary.GetNumberOfBlocks())}
deform = filters.vtkMLSDeformFilter()
deform.SetInputData(0, mesh)
regions = []
for name, role in ROLES:
    region = filters.vtkConstraintRegion()
    region.SetInputData(patches[name])
    region.SetRole(role)
    region.SetSelectionMode(filters.vtkConstraintRegion.AllPoints)
    if role == filters.vtkConstraintRegion.Handle:
        region.SetTranslation(0.1, 0, 0)
    regions.append(region)
    deform.AddInputConnection(1, region.GetOutputPort())
deform.Update()
field = deform.GetOutputDataObject(0).GetFieldData()
if field.GetAbstractArray('DeformationError') is not None or field.GetArray('InvertedCells') is None:
    raise RuntimeError('the deformation or its quality verdict failed')
writer = readers.vtkOpenFOAMCaseWriter()
writer.SetInputConnection(deform.GetOutputPort())
writer.SetFileName(os.path.join(out, 'variant', 'case.foam'))
writer.SetLinkUnchangedFiles(1)
if writer.Write() != 1 or writer.GetErrorCode() != 0:
    raise RuntimeError('the variant was not written')
result['first_s'] = time.time() - start
result['verdict'] = {k: field.GetArray(k).GetTuple1(0) for k in ('InvertedCells', 'MaxNonOrthogonality', 'MaxSkewness')}
print('VTKFIRST ' + json.dumps(result), flush=True)
