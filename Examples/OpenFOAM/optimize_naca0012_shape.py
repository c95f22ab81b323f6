"""A shape optimization with local variables and constraint functions: the NACA 0012 laminar drag
case of OpenFOAM's adjoint tutorial (Re 1000 at 2 degrees), its section's shape free at 10 chord
stations on each surface (20 local variables, naca0012.shape_deformation: each a line across the
depth moving along y, +-0.01 chords), the drag minimized by scipy's SLSQP with OpenFOAM's adjoint
gradient chained through the exact dX/dp (DesignVariables.totalSensitivity), under the constraints
of mlsdeform.DesignConstraints with their exact gradients:
  - the thickness at the 10 stations at least the baseline's (addThicknessConstraints1D),
  - the enclosed volume (the section's area) at least the baseline's (addTriangulatedVolumeConstraint),
  - the leading and trailing edges held: at the first and the last station the upper and lower
    control points move by the same amount opposite ways (addLeTeConstraints: their midpoint
    stays, p_upper + p_lower = 0 with both directions +y),
  - the mesh quality: the KS-aggregated non-orthogonality at most 65 degrees (addMeshQualityConstraint;
    checkMesh's limit is 70).
Every variant's mesh gets checkMesh's verdict; a variant that fails it is not run.

Usage: pvpython optimize_naca0012_shape.py PLUGIN WORK [--iterations 15] [--primal 3000] [--adjoint 3000] [--cold]

Prints one line per adjoint run (J, the constraints, the verdict) and the answer: which
constraints end active (bounds on the variables too), the KKT residual (the projected gradient
of the Lagrangian) and how far the nose and the tail themselves moved, and writes
WORK/history.csv (per run: J and every constraint's value) and WORK/naca0012_shape.png (the
baseline and the optimized sections, the surface sensitivity dJ/dy along them, J's history and
the constraints' history against their bounds). A run starts from
the previous run's fields unless --cold (then J after a fixed number of iterations depends on the
shape alone, as the suite's reduced run needs).
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
parser.add_argument('--iterations', type=int, default=15, help="SLSQP's iterations at most (default 15)")
parser.add_argument('--primal', type=int, default=3000, help='primal iterations per run (at most; residuals 1e-7 stop it)')
parser.add_argument('--adjoint', type=int, default=3000, help='adjoint iterations per run (at most)')
parser.add_argument('--cold', action='store_true', help="every run from the tutorial's initial fields")
parser.add_argument('--replot', action='store_true', help="only the picture again, from a finished run's WORK/history.csv")
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mlsdeform  # noqa: E402
import naca0012  # noqa: E402
from scipy.optimize import minimize  # noqa: E402

STATIONS = 0.5 * (1 - np.cos(np.linspace(0.08, 0.92, 10) * np.pi))   # cosine spacing, x/c 0.016 .. 0.98
MAX_NON_ORTHOGONALITY = 65.0

work = os.path.abspath(args.work)
began = time.perf_counter()
foam_file = naca0012.source_case(work, args.primal, args.adjoint)
deformed, dvs = naca0012.shape_deformation(foam_file, STATIONS)
names = dvs.getVarNames()
bounds = [dvs.getBounds()[n] for n in names]
cons = mlsdeform.DesignConstraints(dvs)
surface = ['suction', 'pressure']
cons.addThicknessConstraints1D('thickness', [[STATIONS[0], 0, 0.5], [STATIONS[-1], 0, 0.5]], len(STATIONS), [0, 1, 0],
                               surface=surface, lower=1.0, upper=3.0)
cons.addTriangulatedVolumeConstraint('volume', surface=surface, axis=[0, 0, 1], lower=1.0, upper=3.0)
cons.addLeTeConstraints('leadingEdge', 'upper_0', 'lower_0')
cons.addLeTeConstraints('trailingEdge', 'upper_%d' % (len(STATIONS) - 1), 'lower_%d' % (len(STATIONS) - 1))
cons.addMeshQualityConstraint('quality', 'nonOrthogonality', upper=MAX_NON_ORTHOGONALITY)
print('%d variables; constraints: %s' % (len(names), ', '.join(cons.getConstraintNames())), flush=True)

history, cache, last = [], {}, {'case': None}


def run(p):
    """The adjoint run of the design p (cached): J and dJ/dp as an array."""
    key = tuple(np.round(p, 12))
    if key not in cache:
        label = 'run%d' % (len(history) + 1)
        result = naca0012.run_variant(deformed, dvs, dict(zip(names, map(float, p))), os.path.join(work, label), args.primal,
                                      args.adjoint, None if args.cold else last['case'])
        if not result['ok']:   # SLSQP's line search may step there: the KS constraint should keep it away
            raise RuntimeError('the design %s fails the mesh-quality thresholds: %s' % (list(p), result['quality']))
        funcs = {}
        cons.evalFunctions(funcs)
        last['case'] = result['case']
        history.append(dict(run=len(history) + 1, J=result['J'], seconds=round(time.perf_counter() - began),
                            thickness_min=float(np.min(funcs['thickness'])), volume=float(funcs['volume'][0]),
                            leading_edge=float(funcs['leadingEdge'][0]), trailing_edge=float(funcs['trailingEdge'][0]),
                            quality=float(funcs['quality'][0]), max_non_orthogonality=result['quality']['MaxNonOrthogonality'],
                            checkMesh=naca0012.checkmesh(result['case'])[0], **dict(zip(names, map(float, p)))))
        h = history[-1]
        print('run %2d: J %.8f, thickness/baseline >= %.4f, volume/baseline %.4f, LE/TE relations %.1e %.1e, '
              'non-orthogonality %.2f (KS %.2f), checkMesh %s, %.0f s'
              % (h['run'], h['J'], h['thickness_min'], h['volume'], h['leading_edge'], h['trailing_edge'],
                 h['max_non_orthogonality'], h['quality'], 'OK' if h['checkMesh'] else 'FAILED', h['seconds']), flush=True)
        cache[key] = (result['J'], np.array([result['gradient'][n] for n in names]), result['case'])
    return cache[key]


def picture(x, case, J0):
    """WORK/naca0012_shape.png: the baseline and the design x, coloured by the case's dJ/dy, the
    surfaces' motion along the chord with the control points', J's history and the constraints'
    (each over its bound: at most 1 holds it)."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    dvs.setDesignVars(dict(zip(names, map(float, x))))
    X = dvs.update().copy()
    dJdX = mlsdeform.readFoamSensitivity(deformed, field=naca0012.FIELD, case=case)   # the design's own case
    held = dvs.getControlPoints()
    dvs.setDesignVars(dict.fromkeys(names, 0.0))
    X0 = dvs.update()
    section = (np.linalg.norm(dJdX, axis=1) > 0) & (X0[:, 2] < 0.5)   # the wall's points at z = 0
    order = np.argsort(np.arctan2(X0[section, 1], X0[section, 0] - 0.5))
    figure, (shape, motion, runs, bounds_held) = plt.subplots(1, 4, figsize=(17, 3.8), gridspec_kw={'width_ratios': [1.6, 1.6, 1, 1]})
    shape.plot(X0[section, 0][order], X0[section, 1][order], '--', color='gray', label='NACA 0012 (baseline)')
    colours = shape.scatter(X[section, 0], X[section, 1], c=dJdX[section, 1], s=3, cmap='coolwarm', label='optimized')
    figure.colorbar(colours, ax=shape, label='dJ/dy (the last run)')
    shape.set_xlabel('x / c')
    shape.set_title('sections (z = 0; y stretched)', fontsize=10)
    shape.legend(fontsize=7)
    for side, colour in (('upper', 'tab:red'), ('lower', 'tab:blue')):
        points = section & ((X0[:, 1] > 0) if side == 'upper' else (X0[:, 1] < 0))
        along = np.argsort(X0[points, 0])
        motion.plot(X0[points, 0][along], (X - X0)[points, 1][along], '-', color=colour, label='%s surface' % side)
        controls = np.array([held[n][0][0] for n in names if n.startswith(side)])
        values = np.array([x[i] for i, n in enumerate(names) if n.startswith(side)])
        motion.plot(controls[:, 0], values, 'o', color=colour, markersize=4)
    motion.axhline(0, color='gray', linewidth=0.5)
    motion.set_xlabel('x / c')
    motion.set_ylabel('y motion (chords)')
    motion.set_title('the surfaces\' motion (dots: the variables)', fontsize=10)
    motion.legend(fontsize=7)
    runs.plot([h['run'] for h in history], [h['J'] / J0 for h in history], 'o-')
    runs.set_xlabel('adjoint run')
    runs.set_ylabel('J / J baseline')
    runs.set_title('drag history (SLSQP)', fontsize=10)
    number = [h['run'] for h in history]
    for key, label in (('thickness_min', 'least thickness: 1 / (t / t0)'), ('volume', 'volume: 1 / (V / V0)'),
                       ('quality', 'KS non-orthogonality / %g' % MAX_NON_ORTHOGONALITY)):
        ratio = [(h[key] / MAX_NON_ORTHOGONALITY) if key == 'quality' else 1 / h[key] for h in history]
        bounds_held.plot(number, ratio, 'o-', markersize=3, label=label)
    bounds_held.axhline(1, color='gray', linestyle='--', linewidth=0.8)
    bounds_held.set_xlabel('adjoint run')
    bounds_held.set_title('constraints / bounds (<= 1 holds)', fontsize=10)
    bounds_held.legend(fontsize=6)
    figure.suptitle('NACA 0012, 20 local variables, thickness/volume/LE-TE/mesh-quality constraints: MLS Deform + OpenFOAM adjoint',
                    fontsize=9)
    figure.tight_layout()
    figure.savefig(os.path.join(work, 'naca0012_shape.png'), dpi=110)
    print('written: %s' % os.path.join(work, 'naca0012_shape.png'))


if args.replot:
    with open(os.path.join(work, 'history.csv')) as f:
        history = [{k: float(v) if k not in ('checkMesh',) else v == 'True' for k, v in row.items()} for row in csv.DictReader(f)]
    last = history[-1]
    picture(np.array([last[n] for n in names]), os.path.join(work, 'run%d' % int(last['run'])), history[0]['J'])
    sys.exit(0)


p0 = np.zeros(len(names))
J0 = run(p0)[0]
print("the mesh-quality constraint's KS exceeds the largest non-orthogonality by at most %.2f degrees" % cons.getBiasBound('quality'))
result = minimize(lambda p: run(p)[0] / J0, p0, jac=lambda p: run(p)[1] / J0, bounds=bounds, method='SLSQP',
                  constraints=cons.getScipyConstraints(), options={'maxiter': args.iterations, 'ftol': 1e-6})

# The answer and why: the active constraints and the KKT residual at SLSQP's last design
J, g, case = run(result.x)
dvs.setDesignVars(dict(zip(names, map(float, result.x))))
funcs, sens = {}, {}
cons.evalFunctions(funcs)
cons.evalFunctionsSens(sens)
active, rows = [], []
for name, (lo, hi) in cons.getBounds().items():
    value = np.atleast_1d(funcs[name])
    jacobian = np.array([np.atleast_1d(sens[name][n]) for n in names]).T   # (entries, variables)
    for k, v in enumerate(value):
        for bound, side in ((lo, 'its lower bound'), (hi, 'its upper bound')) if lo != hi else ((lo, 'its value'),):
            if bound is not None and abs(v - bound) <= 1e-4 * max(1.0, abs(bound)):
                active.append('%s[%d] at %s %.4g' % (name, k, side, bound))
                rows.append(jacobian[k])
at_bound = [n for n, x, (lo, hi) in zip(names, result.x, bounds) if abs(x - lo) < 1e-7 or abs(x - hi) < 1e-7]
free = np.array([n not in at_bound for n in names])
gradient = g / J0
if rows and free.any():   # the multipliers by least squares over the free variables: grad J = sum lambda_i grad c_i
    A = np.array(rows)[:, free].T
    multipliers = np.linalg.lstsq(A, gradient[free], rcond=None)[0]
    residual = gradient[free] - A @ multipliers
else:
    multipliers, residual = np.array([]), gradient[free]
print('SLSQP: %s after %d iterations, %d adjoint runs, %.0f s' % (result.message, result.nit, len(history),
                                                                  time.perf_counter() - began))
print('J %.8f -> %.8f (%+.2f%%)' % (J0, J, 100 * (J / J0 - 1)))
print('active constraints: %s' % ('; '.join(active) or 'none'))
print('variables at a bound: %s' % (', '.join(at_bound) or 'none'))
print('KKT: |dJ/dp| %.3g over the free variables, |dJ/dp - sum lambda dc/dp| %.3g (multipliers %s)' % (
    np.linalg.norm(gradient[free]), np.linalg.norm(residual), ', '.join('%.3g' % m for m in multipliers)))
X = dvs.update().copy()
dvs.setDesignVars(dict.fromkeys(names, 0.0))
X0 = dvs.update()
dvs.setDesignVars(dict(zip(names, map(float, result.x))))
wall = np.linalg.norm(mlsdeform.readFoamSensitivity(deformed, field=naca0012.FIELD, case=case), axis=1) > 0   # the wall's points
for end, at in (('nose (x = 0)', np.argmin(np.where(wall, X0[:, 0], np.inf))), ('tail (x = 1)', np.argmax(np.where(wall, X0[:, 0], -np.inf)))):
    print('the %s moved by (%.2g, %.2g) chords (the edge relations hold the control points\' midpoints at x/c %.3f, %.3f)'
          % (end, *(X - X0)[at, :2], STATIONS[0], STATIONS[-1]))

with open(os.path.join(work, 'history.csv'), 'w', newline='') as f:
    writer = csv.DictWriter(f, fieldnames=list(history[0]))
    writer.writeheader()
    writer.writerows(history)

picture(result.x, case, J0)
print('written: %s' % os.path.join(work, 'history.csv'))
# the verdict (exit code 1 otherwise): J decreased, every constraint holds at the end (SLSQP's
# tolerance), checkMesh passed every run
feasible = all(np.all(np.atleast_1d(funcs[n]) >= (lo if lo is not None else -np.inf) - 1e-6) and
               np.all(np.atleast_1d(funcs[n]) <= (hi if hi is not None else np.inf) + 1e-6) for n, (lo, hi) in cons.getBounds().items())
decreased = J < J0
meshes = all(h['checkMesh'] for h in history)
print('J decreased: %s; every constraint holds: %s; checkMesh passed every variant: %s' % (decreased, feasible, meshes))
sys.exit(0 if decreased and feasible and meshes else 1)
