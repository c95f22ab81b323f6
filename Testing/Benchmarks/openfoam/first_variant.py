"""The first variant on a plain VTK pipeline, for the design-of-experiments benchmark
(run-doe-benchmark.sh): the same case, regions and settings as doe_benchmark.py's set-up (the
hull a Handle translated by 0.1 m, inlet and outlet Fixed, the other planes Slip), through
Examples/OpenFOAM/vtk_variant.py in Debian's python3, without ParaView's server manager (what a
VTK C++ pipeline pays too). Timed from the process's start to the variant written (a linked case
in OUT_FOLDER/variant), as doe_benchmark.py's first variant. Prints one JSON line (VTKFIRST {...}).
Usage: python3 vtk_first_variant.py PLUGIN_FOLDER EXAMPLES_OPENFOAM_DIR CASE.foam OUT_FOLDER"""
import json
import os
import sys
import time

start = time.time()
plugin_folder, examples, foam, out = sys.argv[1:5]
sys.path.insert(0, examples)
import vtk_variant  # noqa: E402

result = {'startup_s': time.time() - start}
_, deform, _ = vtk_variant.morph(plugin_folder, foam, ['hull'], (0.1, 0, 0), ['inlet', 'outlet'],
                                 ['sideYmin', 'sideYmax', 'bottom', 'top'], decompose_polyhedra=False)  # checkMesh's own cells
field = deform.GetOutputDataObject(0).GetFieldData()
if field.GetArray('InvertedCells') is None:
    raise RuntimeError('MLS Deform reports no quality verdict')
if vtk_variant.save_variant(plugin_folder, deform, os.path.join(out, 'variant', 'case.foam')).GetErrorCode() != 0:
    raise RuntimeError('the variant was not written')
result['first_s'] = time.time() - start
result['verdict'] = {k: field.GetArray(k).GetTuple1(0) for k in ('InvertedCells', 'MaxNonOrthogonality', 'MaxSkewness')}
print('VTKFIRST ' + json.dumps(result), flush=True)
