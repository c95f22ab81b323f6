"""Gradient-based shape optimization of the NACA 0012 laminar drag case with OpenFOAM's adjoint:
the design variables of naca0012.py (angle of attack and thickness, bounded), each iteration a
variant case written by MLS Deform and rejected if its mesh fails the quality thresholds (DAFoam's:
no inverted cell, non-orthogonality at most 70, skewness at most 4), then adjointOptimisationFoam
on it (primal, adjoint and the surface sensitivity), dJ/dp = sum_i dJ/dX_i . dX_i/dp through
mlsdeform.readFoamSensitivity and DesignVariables.totalSensitivity, and a projected
steepest-descent step in the variables scaled to their bounds with a backtracking (Armijo) line
search: a trial whose mesh fails or whose J does not decrease enough is rejected and the step
halved. J decreases from one accepted iterate to the next by construction; the drag optimum
within the bounds is the thinnest airfoil aligned with the flow (aoa -2 degrees, thickness -0.3).

Usage: pvpython optimize_naca0012.py PLUGIN WORK [--iterations 6] [--primal 3000] [--adjoint 3000]
       [--cold]
Prints a table (iteration, p, J, |dJ/dp|, inverted cells, max non-orthogonality) and writes
WORK/history.csv and WORK/J.png. A trial's primal starts from the last accepted solution (its
fields copied into the trial's initial time; --cold: from the tutorial's initial fields, so that
J after a fixed number of iterations is a function of p alone, as the reduced test needs).
"""
import argparse
import csv
import os
import sys
import time

import numpy as np
from paraview.simple import LoadPlugin

parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
parser.add_argument('plugin')
parser.add_argument('work')
parser.add_argument('--iterations', type=int, default=6, help='accepted steps (default 6)')
parser.add_argument('--primal', type=int, default=3000, help='primal iterations per run (at most; residuals 1e-7 stop it)')
parser.add_argument('--adjoint', type=int, default=3000, help='adjoint iterations per run (at most)')
parser.add_argument('--step', type=float, default=0.5, help='first step length in the scaled variables (bounds: -1 to 1)')
parser.add_argument('--cold', action='store_true', help="every run from the tutorial's initial fields")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False)
here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import naca0012  # noqa: E402

ARMIJO = 1e-4         # sufficient decrease: J(p_new) <= J(p) + ARMIJO g . (p_new - p)
SHRINK, GROW = 0.5, 1.5
MAX_TRIALS = 6        # halvings per iteration before giving up

work = os.path.abspath(args.work)
began = time.perf_counter()
source, deformed, dvs = naca0012.source_deformation(work, args.primal, args.adjoint)
names = dvs.getVarNames()
bounds = dvs.getBounds()
lower = np.array([bounds[n][0] for n in names])
upper = np.array([bounds[n][1] for n in names])
scale = (upper - lower) / 2    # the step is taken in p / scale: each variable's range is 2 wide


def evaluate(p, label, previous):
    """The variant at p (naca0012.run_variant) in WORK/label, from the previous accepted run's
    fields unless --cold: a dict of the results, with ok False (and no J) for a variant the
    thresholds reject."""
    result = naca0012.run_variant(deformed, dvs, dict(zip(names, p)), os.path.join(work, label), args.primal, args.adjoint,
                                  None if args.cold else previous)
    result['p'] = np.array(p)
    if result['ok']:
        result['gradient'] = np.array([result['gradient'][n] for n in names])
    return result


def row(iteration, r):
    q = r['quality']
    return dict(iteration=iteration, **{n: float(v) for n, v in zip(names, r['p'])}, J=r['J'],
                gradient_norm=float(np.linalg.norm(r['gradient'])), inverted_cells=q['InvertedCells'],
                max_non_orthogonality=q['MaxNonOrthogonality'], checkMesh=naca0012.checkmesh(r['case'])[0],
                seconds=time.perf_counter() - began)


def show(entry):
    print('%9d  %s  %12.8f  %10.4g  %8d  %8.2f  %9s  %7.0f' % (
        entry['iteration'], '  '.join('%9.4f' % entry[n] for n in names), entry['J'], entry['gradient_norm'],
        entry['inverted_cells'], entry['max_non_orthogonality'], 'OK' if entry['checkMesh'] else 'FAILED',
        entry['seconds']), flush=True)


print('%9s  %s  %12s  %10s  %8s  %8s  %9s  %7s' % ('iteration', '  '.join('%9s' % n for n in names), 'J', '|dJ/dp|',
                                                   'inverted', 'non-orth', 'checkMesh', 'seconds'), flush=True)
current = evaluate(np.zeros(len(names)), 'iteration0', None)
if not current['ok']:
    sys.exit('the undeformed case fails the mesh-quality thresholds: %s' % current['quality'])
history = [row(0, current)]
show(history[-1])
length = args.step
for iteration in range(1, args.iterations + 1):
    direction = -current['gradient'] * scale              # steepest descent in p / scale, projected:
    direction[(current['p'] <= lower) & (direction < 0)] = 0  # no push against an active bound
    direction[(current['p'] >= upper) & (direction > 0)] = 0
    if not np.any(direction):
        print('the projected gradient is zero: a bound-constrained optimum at iteration %d' % (iteration - 1))
        break
    direction /= np.linalg.norm(direction)
    accepted = None
    tried = None
    for trial in range(MAX_TRIALS):
        p = np.clip(current['p'] + length * direction * scale, lower, upper)
        while tried is not None and np.array_equal(p, tried) and length > 1e-6:
            length *= SHRINK                                # clipped to the same point: no new trial there
            p = np.clip(current['p'] + length * direction * scale, lower, upper)
        if np.allclose(p, current['p'], rtol=0, atol=1e-12):
            break                                           # the bounds stop the descent
        tried = p
        candidate = evaluate(p, 'iteration%d_trial%d' % (iteration, trial), current['case'])
        if candidate['ok'] and candidate['J'] <= current['J'] + ARMIJO * current['gradient'] @ (p - current['p']):
            accepted = candidate
            break
        print('           rejected: %s' % ('J %.8f' % candidate['J'] if candidate['ok'] else
                                            'mesh fails the thresholds %s' % candidate['quality']), flush=True)
        length *= SHRINK
    if accepted is None:
        print('no descent step found: stopped at iteration %d' % (iteration - 1))
        break
    current = accepted
    history.append(row(iteration, current))
    show(history[-1])
    length *= GROW
dvs.setDesignVars({n: 0.0 for n in names})

with open(os.path.join(work, 'history.csv'), 'w', newline='') as f:
    writer = csv.DictWriter(f, fieldnames=list(history[0]))
    writer.writeheader()
    writer.writerows(history)
import matplotlib  # noqa: E402
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
figure, axes = plt.subplots(figsize=(5, 3.5))
axes.plot([h['iteration'] for h in history], [h['J'] for h in history], 'o-')
axes.set_xlabel('iteration')
axes.set_ylabel('J (drag objective)')
axes.set_title('NACA 0012 drag: MLS Deform + OpenFOAM adjoint')
figure.tight_layout()
figure.savefig(os.path.join(work, 'J.png'), dpi=120)
print('J %.8f -> %.8f in %d iterations, %.0f s; %s and %s' % (history[0]['J'], history[-1]['J'], len(history) - 1,
                                                             time.perf_counter() - began,
                                                             os.path.join(work, 'history.csv'), os.path.join(work, 'J.png')))
# the verdict (exit code 1 otherwise): J decreased, and checkMesh passed every accepted variant
decreased = len(history) > 1 and all(b['J'] < a['J'] for a, b in zip(history, history[1:]))
meshes = all(h['checkMesh'] for h in history)
print('J decreased at every iteration: %s; checkMesh passed every variant: %s' % (decreased, meshes))
sys.exit(0 if decreased and meshes else 1)
