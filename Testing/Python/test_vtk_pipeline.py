"""A plain VTK pipeline in python3, without ParaView's server manager: ParaView's VTK modules and
the plugin's wrapped filters and case writer (mlsdeform_wrapping, beside the plugin) read the
sphereChannel case (built here), deform it (the sphere moved by (0.05, 0, 0.02), inlet and outlet
Fixed, the other planes Slip) and write a linked variant case. The variant's points file must be,
byte for byte, the one pvpython writes through mlsdeform.foam (Examples/OpenFOAM/morph_case.py with
its defaults); a bad target is refused with nothing written. The batch benchmark's first variant
runs this way (Testing/Benchmarks/openfoam/vtk_first_variant.py).
Usage: python3 test_vtk_pipeline.py PLUGIN_FILE EXAMPLES_OPENFOAM_DIR WORK_DIR"""
import os
import subprocess
import sys

plugin, examples, work = sys.argv[1:4]
sys.path.insert(0, os.path.dirname(os.path.abspath(plugin)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet  # noqa: E402
from vtkmodules.vtkIOGeometry import vtkOpenFOAMReader  # noqa: E402
import mlsdeform_wrapping.MLSDeformFilters as filters  # noqa: E402
import mlsdeform_wrapping.MLSDeformReaders as readers  # noqa: E402

from checks import check, finish  # noqa: E402

case = os.path.join(work, 'case')
subprocess.run(['bash', os.path.join(examples, 'make-case.sh'), case], check=True)
ROLES = [('body', filters.vtkConstraintRegion.Handle), ('inlet', filters.vtkConstraintRegion.Fixed),
         ('outlet', filters.vtkConstraintRegion.Fixed)] + [(p, filters.vtkConstraintRegion.Slip) for p in ('ground', 'top', 'front', 'back')]

reader = vtkOpenFOAMReader()
reader.SetFileName(os.path.join(case, 'case.foam'))
reader.SetDecomposePolyhedra(1)   # ParaView's default, as morph_case.py reads it
reader.UpdateInformation()
for i in range(reader.GetNumberOfPatchArrays()):
    name = reader.GetPatchArrayName(i)
    reader.SetPatchArrayStatus(name, 1 if name == 'internalMesh' or name.replace('patch/', '') in dict(ROLES) else 0)
reader.Update()
mesh = reader.GetOutput()
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
        region.SetTranslation(0.05, 0, 0.02)
    regions.append(region)
    deform.AddInputConnection(1, region.GetOutputPort())
writer = readers.vtkOpenFOAMCaseWriter()
writer.SetInputConnection(deform.GetOutputPort())
writer.SetFileName(os.path.join(work, 'vtk-variant', 'case.foam'))
writer.SetLinkUnchangedFiles(1)
check(writer.Write() == 1 and writer.GetErrorCode() == 0, 'the VTK pipeline writes the variant case')
check('paraview.servermanager' not in sys.modules and 'paraview.simple' not in sys.modules,
      "the pipeline ran without ParaView's server manager")
polymesh = os.path.join(work, 'vtk-variant', 'constant', 'polyMesh')
check(os.path.isfile(os.path.join(polymesh, 'points')) and not os.path.islink(os.path.join(polymesh, 'points')),
      'the variant holds its own points file')
check(os.path.islink(os.path.join(polymesh, 'faces')), "and links the source's unchanged faces")

subprocess.run(['pvpython', '--no-mpi', os.path.join(examples, 'morph_case.py'), plugin, os.path.join(case, 'case.foam'),
                os.path.join(work, 'pv-variant')], check=True)
with open(os.path.join(polymesh, 'points'), 'rb') as a, open(os.path.join(work, 'pv-variant', 'constant', 'polyMesh', 'points'), 'rb') as b:
    mine, theirs = a.read(), b.read()
with open(os.path.join(case, 'constant', 'polyMesh', 'points'), 'rb') as source:
    check(mine != source.read(), "the variant's points moved")
check(mine == theirs, "its points file is pvpython's, byte for byte (%d bytes)" % len(mine))

# a target folder that does not exist: refused, nothing written
bad = readers.vtkOpenFOAMCaseWriter()
bad.SetInputConnection(deform.GetOutputPort())
bad.SetFileName(os.path.join(work, 'no-such-folder', 'variant', 'case.foam'))
bad.Write()
check(bad.GetErrorCode() != 0 and not os.path.exists(os.path.join(work, 'no-such-folder')),
      'a variant in a folder that does not exist is refused, and nothing is written')
finish()
