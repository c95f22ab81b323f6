"""A structural shape optimization with local shape variables: a steel plate (10 x 4 x 1 mm) with
a hole of radius 1 mm in its middle, clamped at x = 0 and pulled along x at x = 10, made as stiff as
it can be (its compliance f . u minimized) while its mass stays the start's. The hole's outline is
free: 12 control points around it (DesignVariables.addLocalDV, at 30 degree steps), each a line
through the thickness (the plate is its section extruded in layers, the line axis is z: the hole
stays a prism), each moving by its variable p along the outline's normal (out of the solid: p > 0
moves the outline into the hole, the radius there is about 1 - p); the outline between them bends
smoothly. The exact structural gradients (mlsdeform.exactSensitivity: the compliance is
self-adjoint, so one ccx run a design) chained through dX/dp; the mass held by
DesignConstraints.addMeshVolumeConstraint (the mesh's elements as ccx integrates them, times the
density) and the FEM verdict's least scaled Jacobian kept at least 0.2 by its KS constraint
(addMeshQualityConstraint);
scipy's SLSQP. Every design run is a variant deck that ccx solves and that passes the FEM verdict.

    python3 optimize_hole.py PLUGIN_FOLDER WORK [--quick] [--validate]

What the answer should be: a hole in a plate under uniaxial tension costs stiffness; for an
elliptical hole of semi-axes a along the load and b across it, the extra compliance of a large
plate is proportional to b (b + 2 a) (plane stress: pi sigma^2 t b (b + 2a) / E, a crack for a = 0,
3 pi r^2 for the circle). With the area pi a b held (the mass), that is b^2 + 2 r^2: the smaller
the hole's width across the load, the stiffer the plate. So the optimizer should stretch the hole
along the load into a slot, pulling the outline in at 90 and 270 degrees and pushing it out at 0 and
180, symmetric about the load's axis y = 2, as far as the bounds (and the mesh quality) let it.

Writes WORK/history.csv (one row per ccx run: the variables, compliance, mass, least scaled
Jacobian), WORK/optimize_hole.png (the outlines at the start and at the end, and the history) and
the best design's deck WORK/best/plate.inp. --validate first checks dJ/dp of three control points
against central differences of ccx's responses (h and h/2). --quick: a coarse mesh
and 3 iterations (the test suite's run).
"""
import argparse
import csv
import os
import runpy
import sys

# A python3 without numpy, scipy or VTK hands the run to Debian's python3 or pvpython (the plugin
# folder's mlsdeform/interpreter.py), before numpy loads.
if len(sys.argv) > 1 and os.path.isfile(os.path.join(sys.argv[1], 'mlsdeform', 'interpreter.py')):
    runpy.run_path(os.path.join(sys.argv[1], 'mlsdeform', 'interpreter.py'))['handOver'](
        ('numpy', 'scipy', 'matplotlib', 'vtkmodules'), __file__, 'optimize_hole')
import numpy as np  # noqa: E402

CENTRE, RADIUS = (5.0, 2.0), 1.0
ANGLES = np.arange(12) * 30.0   # the control points' positions on the outline, degrees from +x
BOUND = 0.3                     # mm each control point may move in or out
LEAST_SCALED_JACOBIAN = 0.2     # the KS constraint's bound: the verdict's threshold 0.1 and a margin


def variables():
    """The hole's local variables in plate_design's form: p_0 .. p_11 at ANGLES."""
    points = [[CENTRE[0] + RADIUS * np.cos(np.radians(a)), CENTRE[1] + RADIUS * np.sin(np.radians(a)), 0.0] for a in ANGLES]
    return {'p': dict(bodies=['hole1'], local=dict(points=points, direction='normal', axis=[0, 0, 1]),
                      lower=-BOUND, upper=BOUND)}


def outline(design, X):
    """The hole's outline on the plate's bottom face (z = 0) at the points X: (angles, x, y), sorted
    by angle about the hole's centre."""
    import plate
    from vtkmodules.util.numpy_support import vtk_to_numpy
    ids = vtk_to_numpy(design.deform.GetOutputDataObject(0).GetPointData().GetArray('NodeId'))
    row = {int(n): i for i, n in enumerate(ids)}
    hole = np.array([row[n] for n in plate.node_set(os.path.join(os.path.dirname(design.deck), 'mesh.inp'), 'hole1')])
    bottom = hole[np.abs(X[hole, 2]) < 1e-9]
    angles = np.degrees(np.arctan2(X[bottom, 1] - CENTRE[1], X[bottom, 0] - CENTRE[0])) % 360
    order = np.argsort(angles)
    return angles[order], X[bottom[order], 0], X[bottom[order], 1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('plugin', help="the MLSDeform plugin's folder (it holds the mlsdeform package)")
    parser.add_argument('work', help='where the decks, the history and the plot go')
    parser.add_argument('--quick', action='store_true', help='a coarse mesh and 3 iterations')
    parser.add_argument('--validate', action='store_true', help='check dJ/dp against central differences first')
    arguments = parser.parse_args()
    sys.path.insert(0, arguments.plugin)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import mlsdeform
    import plate
    import plate_design
    from scipy.optimize import minimize

    work = os.path.abspath(arguments.work)
    source = os.path.join(work, 'source')
    plate.mesh_plate(source, holes=(CENTRE + (RADIUS,),), size=0.5 if arguments.quick else 0.35,
                     layers=2 if arguments.quick else 3)
    deck = plate.write_analysis(source, force=1000.0, dof=1, double=True)
    design = plate_design.PlateDesign(deck, work, variables=variables(), responses=(('COMPLIANCE', ''), ('MASS', '')),
                                      exact=True, fixed=('fixed', 'load'))
    names = design.dvs.getVarNames()
    agree = True
    if arguments.validate:
        # central differences with h and h/2: D(h/2)'s O(h^2) error is a third of D(h) - D(h/2), so
        # the chain agrees when it is within that spread of D(h/2) (or within ccx's round-off)
        rows = plate_design.validate(design, steps=(2e-2, 1e-2), variables=['p_0', 'p_1', 'p_3'])
        print(plate_design.table(rows), flush=True)
        gaps = [(abs(chain - d[1e-2]), abs(d[2e-2] - d[1e-2]) + 1e-6 * abs(d[1e-2])) for _, _, chain, d in rows]
        agree = all(gap <= spread for gap, spread in gaps)
        print('the chained dJ/dp within the central differences\' spread: %s' % agree, flush=True)
    constraints = mlsdeform.DesignConstraints(design.dvs)
    constraints.addMeshVolumeConstraint('mass', density=plate.DENSITY, lower=1.0, upper=1.0)   # the start's, as ccx's MASS
    constraints.addMeshQualityConstraint('quality', 'scaledJacobian', lower=LEAST_SCALED_JACOBIAN)

    zero = dict.fromkeys(names, 0.0)
    start, _, start_quality = design.evaluate(zero, 'start')
    X0 = design.dvs.update().copy()
    history, cache = [], {}

    class Rejected(Exception):
        """A trial design whose mesh fails the FEM verdict: it is not run."""

    def evaluate(p):
        key = tuple(np.round(p, 12))
        if key not in cache:
            values = dict(zip(names, map(float, p)))
            design.dvs.setDesignVars(values)
            design.dvs.update()
            quality = mlsdeform.meshQuality(design.dvs)
            if not mlsdeform.passes(quality):
                raise Rejected('%d inverted elements, least scaled Jacobian %.3f' % (quality['InvertedCells'],
                                                                                   quality['MinScaledJacobian']))
            J, dJdp, quality = design.evaluate(values, 'current')
            history.append(dict(values, compliance=J['COMPLIANCE'], mass=J['MASS'], MinScaledJacobian=quality['MinScaledJacobian'],
                                valid=mlsdeform.passes(quality)))
            print('run %2d: compliance %.6g N mm (%+.2f%%), mass %+.4f%%, least scaled Jacobian %.3f' % (
                len(history), J['COMPLIANCE'], 100 * (J['COMPLIANCE'] / start['COMPLIANCE'] - 1),
                100 * (J['MASS'] / start['MASS'] - 1), quality['MinScaledJacobian']), flush=True)
            cache[key] = (J, {r: np.array([dJdp[r][n] for n in names]) for r in dJdp}, np.array(p, dtype=float))
        return cache[key]

    # SLSQP within move limits: a step into a design the FEM verdict rejects (the KS constraint is
    # linearized, a long step can fold an element) is not run; SLSQP starts again from the last
    # design run with each variable's move limit halved; when it converges at a move limit, again
    # from there with the limit doubled. Done when SLSQP converges with no move limit active (only
    # the variables' own bounds), or after 12 starts.
    x, limit, iterations = np.zeros(len(names)), 2 * BOUND, 3 if arguments.quick else 40
    for _ in range(12):
        box = [(max(-BOUND, v - limit), min(BOUND, v + limit)) for v in x]
        try:
            result = minimize(lambda p: evaluate(p)[0]['COMPLIANCE'] / start['COMPLIANCE'], x,
                              jac=lambda p: evaluate(p)[1]['COMPLIANCE'] / start['COMPLIANCE'], bounds=box,
                              constraints=constraints.getScipyConstraints(), method='SLSQP',
                              options={'maxiter': iterations, 'ftol': 1e-7})
        except Rejected as rejected:
            x, limit = list(cache.values())[-1][2], limit / 2
            print('a trial design fails the FEM verdict (%s): SLSQP again from run %d, each variable within +-%.3g mm of it'
                  % (rejected, len(history), limit), flush=True)
            continue
        x = result.x
        at_limit = [lo > -BOUND and abs(v - lo) < 1e-7 or hi < BOUND and abs(v - hi) < 1e-7 for v, (lo, hi) in zip(x, box)]
        if arguments.quick or not result.success or not any(at_limit):
            break
        limit = min(2 * limit, 2 * BOUND)
        print('SLSQP converged at a move limit: again from there, each variable within +-%.3g mm' % limit, flush=True)

    # The answer: SLSQP's last design (evaluated again: the variables' state is SLSQP's last call's)
    J, gradients, _ = evaluate(result.x)
    best = dict(zip(names, map(float, result.x)))
    _, quality = design.write(best, 'best')
    X = design.dvs.update()
    values = {}
    constraints.evalFunctions(values)
    # the mesh's mass (as ccx integrates it) is the deck's: ccx's MASS of the best design
    same_mass = abs(values['mass'][0] * start['MASS'] - J['MASS']) <= 1e-12 * J['MASS']
    print('SLSQP: %s after %d iterations, %d ccx runs' % (result.message, result.nit, design.runs))
    print('compliance %.6g -> %.6g N mm (%+.2f%%), mass %.6g -> %.6g t (%+.3f%%), least scaled Jacobian %.3f -> %.3f '
          '(KS %.3f, bound %.2f)' % (start['COMPLIANCE'], J['COMPLIANCE'], 100 * (J['COMPLIANCE'] / start['COMPLIANCE'] - 1),
                                     start['MASS'], J['MASS'], 100 * (J['MASS'] / start['MASS'] - 1),
                                     start_quality['MinScaledJacobian'], quality['MinScaledJacobian'], float(values['quality'][0]),
                                     LEAST_SCALED_JACOBIAN))
    # Why: the KKT conditions. On the free variables dC/dp = lambda_M dM/dp + lambda_Q dQ/dp (Q the
    # mesh-quality constraint, when it is active); a variable at its bound is pushed against it.
    free = np.abs(np.abs(result.x) - BOUND) > 1e-6
    sensitivities = {}
    constraints.evalFunctionsSens(sensitivities)
    dC, dM = gradients['COMPLIANCE'] / start['COMPLIANCE'], gradients['MASS'] / start['MASS']
    dQ = np.array([sensitivities['quality'][n][0] for n in names])
    quality_active = abs(float(values['quality'][0]) - LEAST_SCALED_JACOBIAN) <= 1e-3
    A = np.stack([dM, dQ] if quality_active else [dM], axis=1)
    multipliers = np.linalg.lstsq(A[free], dC[free], rcond=None)[0] if free.any() else np.zeros(A.shape[1])
    multiplier = float(multipliers[0])
    residual = dC - A @ multipliers
    print('active: the mass%s; multipliers %s; per control point (angle, p, where, the KKT residual dC/dp - A lambda, '
          'against |dC/dp| %.3g):' % (' and the mesh quality' if quality_active else '', ', '.join('%.4g' % m for m in multipliers),
                                     np.linalg.norm(dC[free])))
    for n, a, p, r in zip(names, ANGLES, result.x, residual):
        where = 'upper bound (outline pulled in)' if p > BOUND - 1e-6 else 'lower bound (pushed out)' if p < -BOUND + 1e-6 else 'free'
        print('  %-5s %5.0f deg  %+.4f  %-32s %+.3g' % (n, a, p, where, r))
    angles, x, y = outline(design, X)
    a0, x0, y0 = outline(design, X0)
    length, width = np.ptp(x), np.ptp(y)
    print('the hole: %.3f mm along the load, %.3f across it (start %.3f x %.3f); symmetric about y = 2 within %.3g mm' % (
        length, width, np.ptp(x0), np.ptp(y0), float(np.max(np.abs(result.x - result.x[(12 - np.arange(12)) % 12])))))

    with open(os.path.join(work, 'history.csv'), 'w', newline='') as f:
        writer = csv.DictWriter(f, fieldnames=list(history[0]))
        writer.writeheader()
        writer.writerows(history)
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    figure, (shape, runs) = plt.subplots(1, 2, figsize=(10, 4))
    shape.plot(np.append(x0, x0[0]), np.append(y0, y0[0]), '--', color='gray', label='start (circle, r = 1 mm)')
    shape.plot(np.append(x, x[0]), np.append(y, y[0]), '-', color='tab:blue', label='optimized')
    moved = X[[int(np.argmin(np.linalg.norm(X0[:, :2] - [CENTRE[0] + np.cos(np.radians(a)), CENTRE[1] + np.sin(np.radians(a))],
                                            axis=1) + 1e9 * (np.abs(X0[:, 2]) > 1e-9))) for a in ANGLES]]
    shape.plot(moved[:, 0], moved[:, 1], 'o', color='tab:red', label='control points')
    shape.annotate('load', xy=(1.0, 0.5), xytext=(0.86, 0.5), xycoords='axes fraction', va='center', fontsize=8,
                   arrowprops=dict(arrowstyle='->'))
    shape.set_aspect('equal')
    shape.set_xlim(CENTRE[0] - 1.8, CENTRE[0] + 1.8)
    shape.set_title('the hole (z = 0)', fontsize=10)
    shape.legend(fontsize=7, loc='upper center', bbox_to_anchor=(0.5, -0.12), ncol=3)
    index = np.arange(1, len(history) + 1)
    runs.plot(index, [h['compliance'] / start['COMPLIANCE'] for h in history], 'o-', label='compliance / start')
    runs.plot(index, [h['mass'] / start['MASS'] for h in history], 's--', label='mass / start')
    runs.set_xlabel('ccx run')
    runs.legend(fontsize=8)
    runs.set_title('SLSQP history (each run a valid variant)', fontsize=10)
    figure.suptitle('Plate in tension, hole outline free, mass held: MLS Deform local variables + CalculiX', fontsize=10)
    figure.tight_layout()
    figure.savefig(os.path.join(work, 'optimize_hole.png'), dpi=100)
    # the verdict (exit code 1 otherwise): stiffer, and not by the mass (the full run holds it
    # within 0.01%; a quick run's few iterations leave a change whose first-order effect,
    # lambda dM / M0, must be smaller than the compliance's gain), every run a valid variant (the
    # FEM verdict), the hole longer along the load than across it, the gradients checked
    gain = 1 - J['COMPLIANCE'] / start['COMPLIANCE']
    by_mass = abs(multiplier * (J['MASS'] / start['MASS'] - 1))
    stiffer = gain > 0 and (by_mass < gain if arguments.quick else abs(J['MASS'] / start['MASS'] - 1) <= 1e-4)
    valid = all(h['valid'] for h in history)
    stretched = length > width
    print('stiffer by %.2f%% (the mass change accounts for %.3f%%): %s; every variant valid: %s; the hole stretched along '
          'the load: %s' % (100 * gain, 100 * by_mass, stiffer, valid, stretched))
    print('the mesh volume constraint\'s mass is ccx\'s MASS (to 1e-12): %s' % same_mass)
    return 0 if stiffer and valid and stretched and agree and same_mass else 1


if __name__ == '__main__':
    sys.exit(main())
