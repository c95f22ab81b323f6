"""The first variant in pvpython on paraview.simple proxies (mlsdeform.foam), for the
design-of-experiments benchmark (run-doe-benchmark.sh), beside the batch's own first variant on a
plain VTK pipeline: the same case, regions and settings as doe_benchmark.py's set-up (the hull a
Handle translated by 0.1 m, inlet and outlet Fixed, the other planes Slip), timed from the
process's start to the variant written (a linked case in OUT_FOLDER/variant). Prints one JSON
line (FIRSTVARIANT {...}).
Usage: pvpython first_variant.py PLUGIN_FOLDER CASE.foam OUT_FOLDER"""
import json
import os
import sys
import time

start = time.time()
from paraview.simple import LoadPlugin  # noqa: E402

plugin_folder, foam, out = sys.argv[1:4]
LoadPlugin(os.path.join(plugin_folder, 'MLSDeform.so'), remote=False)
from mlsdeform import foam as pipeline  # noqa: E402
from mlsdeform.deformer import deformer  # noqa: E402

result = {'startup_s': time.time() - start}
handle, fixed, slip = ['hull'], ['inlet', 'outlet'], ['sideYmin', 'sideYmax', 'bottom', 'top']
reader = pipeline.open_case(foam, handle + fixed + slip, decompose_polyhedra=False)  # checkMesh's own cells
deform = pipeline.morph(reader, handle, (0.1, 0, 0), fixed, slip)
field = deformer(deform).algorithm.GetOutputDataObject(0).GetFieldData()
if field.GetArray('InvertedCells') is None:
    raise RuntimeError('MLS Deform reports no quality verdict')
pipeline.save_variant(deform, os.path.join(out, 'variant', 'case.foam'), link=True)
result['first_s'] = time.time() - start
result['verdict'] = {k: field.GetArray(k).GetTuple1(0) for k in ('InvertedCells', 'MaxNonOrthogonality', 'MaxSkewness')}
print('FIRSTVARIANT ' + json.dumps(result), flush=True)
