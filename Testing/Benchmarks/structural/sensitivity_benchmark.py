"""The exact structural shape gradient's side of run-structural-sensitivity-benchmark.sh: on a ccx
run of DECK (its result DECK.frd, *NODE FILE, DOUBLE), dJ/dX of the compliance at every node
(vtkCalculixSensitivity: the deck's analysis read, u read from the .frd, every element's
derivative), RUNS times in this process; prints the median and one JSON line (STRUCTSENS {...}).
Usage: python3 sensitivity_benchmark.py PLUGIN_FOLDER DECK RUNS"""
import json
import os
import statistics
import sys
import time

plugin, deck, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
sys.path.insert(0, plugin)
from mlsdeform.deformer import _load_wrapping  # noqa: E402

seconds = []
for _ in range(runs):
    s = _load_wrapping(readers=True).vtkCalculixSensitivity()
    s.SetDeckFileName(deck)
    s.SetResultFileName(deck[:-4] + '.frd')
    s.SetResponse(0)
    began = time.perf_counter()
    if not s.Compute():
        sys.exit(s.GetLastError())
    seconds.append(time.perf_counter() - began)
print('STRUCTSENS ' + json.dumps({'threads': int(os.environ.get('OMP_NUM_THREADS', '0')), 'nodes': s.GetNodeIds().GetNumberOfTuples(),
                                  'seconds': seconds, 'median_s': statistics.median(seconds), 'compliance': s.GetValue()}), flush=True)
