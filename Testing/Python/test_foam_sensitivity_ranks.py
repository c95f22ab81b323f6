"""readFoamSensitivity under MPI: on 2 processes (mpiexec -n 2 pvbatch --symmetric), the NACA 0012
case that Python.FoamSensitivity ran the adjoint on (WORK/source) is spread over the processes
(RedistributeDataSet, which drops the reader's CasePath: source= names it) and deformed; each
process reads the field for its own points. Against the serial run (WORK/reference.npz): each
process's rows are the serial rows at the same positions, bit for bit, except that a mesh point on
both pieces counts on the lower-ranked one only (the rows summed over the processes are the
serial ones), and dJ/dp is the serial one bitwise (the filter sums in one canonical order on
every process). Without source= every process gets the same clear error (no process waits for
another).
Usage: mpiexec -n 2 pvbatch --symmetric test_foam_sensitivity_ranks.py PLUGIN EXAMPLES_OPENFOAM_DIR WORK_DIR"""
import os
import sys

import numpy as np
from paraview.simple import LoadPlugin

plugin, examples, work = sys.argv[1:4]
LoadPlugin(plugin, remote=False)
sys.path.insert(0, examples)
import mlsdeform  # noqa: E402
import naca0012  # noqa: E402
from mlsdeform.ranks import all_reduce, rank  # noqa: E402

failures = []


def check(condition, what):
    print('rank %d: %s%s' % (rank(), 'ok   ' if condition else 'FAIL ', what), flush=True)
    if not condition:
        failures.append(what)


reference = np.load(os.path.join(work, 'reference.npz'))
source = os.path.join(work, 'source')
deformed, dvs = naca0012.deformation(os.path.join(source, 'case.foam'), distribute=True)
check(mlsdeform.ranks.controller() is not None, 'runs on %d processes' % mlsdeform.ranks.controller().GetNumberOfProcesses())
try:
    mlsdeform.readFoamSensitivity(deformed, field=naca0012.FIELD)
    check(False, 'without CasePath and source= a ValueError')
except ValueError as e:
    check('give source=' in str(e), 'without CasePath and source=: %s' % e)

dJdX = mlsdeform.readFoamSensitivity(deformed, field=naca0012.FIELD, source=source)
rest = np.concatenate([np.array(mlsdeform.adjoint._points(d)) for _, d in
                       mlsdeform.adjoint._leaves(dvs._algorithm.GetInputDataObject(0, 0))])
index = {}
for i, x in enumerate(reference['rest']):
    index.setdefault(tuple(x), i)   # a position's first output point, where the serial row is
which = np.array([index.get(tuple(x), -1) for x in rest], dtype=int)
check(len(rest) > 0 and (which >= 0).all(), 'each of the %d points of this piece is a point of the serial input' % len(rest))
rows = np.flatnonzero(np.abs(dJdX).sum(axis=1) > 0)
check(np.array_equal(dJdX[rows], reference['dJdX'][which[rows]]), 'its %d non-zero rows are the serial rows at those positions' % len(rows))
total = all_reduce(dJdX.sum(axis=0), 'sum')
serial = reference['dJdX'].sum(axis=0)
# each mesh point on one process only: the same sum, in another order (round-off: 1e-12 of sum |row|)
check(np.abs(total - serial).max() <= 1e-12 * np.abs(reference['dJdX']).sum() and
      all_reduce(len(rows), 'sum') == np.count_nonzero(np.abs(reference['dJdX']).sum(axis=1) > 0),
      'summed over the processes, the rows are the serial ones (%s vs %s), each mesh point once' % (total, serial))
g = dvs.totalSensitivity(dJdX)
mine = np.array([g[n] for n in dvs.getVarNames()])
check(np.array_equal(mine, reference['dJdp']), 'dJ/dp %s is the serial %s bitwise' % (mine.tolist(), reference['dJdp'].tolist()))

if failures:
    sys.exit('%d check(s) failed' % len(failures))
