"""The structural design loop, worked through: a plate with two holes and rounded corners (Gmsh,
C3D10), clamped at one end and pulled down at the other, made as light as it can be while its tip
deflects at most 2% more than at the start. Design variables on the holes' positions and radii
(translate and scale of their sets) and on the fillets (scale); scipy's SLSQP with the exact
structural gradients (mlsdeform.exactSensitivity: every node's dJ/dX from ccx's displacements and
one adjoint run) chained through MLS Deform's exact dX/dp (DesignVariables.totalSensitivity), or
with --ccx-sensitivities CalculiX's own normal-only shape sensitivities
(mlsdeform.readCalculixSensitivity). Every design is a variant deck that ccx runs, and each must
pass the FEM verdict (no inverted element).

    python3 optimize_plate.py PLUGIN_FOLDER WORK [--quick] [--validate] [--ccx-sensitivities]

Writes WORK/history.csv (one row per ccx run of the optimizer: the variables, mass, tip deflection,
least scaled Jacobian), WORK/optimize_plate.png (mass and deflection per iteration) and the best
design's deck WORK/best/plate.inp. --validate first prints the check of dJ/dp against central
differences of ccx's responses (plate_design.validate). --quick: a coarse mesh and 3 iterations
(the test suite's run).
"""
import argparse
import csv
import os
import runpy
import sys

# A python3 without numpy, scipy or VTK (pyenv's, conda's: first on many PATHs) hands the run to
# Debian's python3 or pvpython (the plugin folder's mlsdeform/interpreter.py), before numpy loads.
if len(sys.argv) > 1 and os.path.isfile(os.path.join(sys.argv[1], 'mlsdeform', 'interpreter.py')):
    runpy.run_path(os.path.join(sys.argv[1], 'mlsdeform', 'interpreter.py'))['handOver'](
        ('numpy', 'scipy', 'matplotlib', 'vtkmodules'), __file__, 'optimize_plate')
import numpy as np  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('plugin', help="the MLSDeform plugin's folder (it holds the mlsdeform package)")
    parser.add_argument('work', help='where the decks, the history and the plot go')
    parser.add_argument('--quick', action='store_true', help='a coarse mesh and 3 iterations')
    parser.add_argument('--validate', action='store_true', help='check dJ/dp against central differences first')
    parser.add_argument('--ccx-sensitivities', action='store_true',
                        help="CalculiX's own normal-only sensitivities instead of the exact gradient")
    arguments = parser.parse_args()
    sys.path.insert(0, arguments.plugin)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import plate_design
    from scipy.optimize import minimize

    work = os.path.abspath(arguments.work)
    exact = not arguments.ccx_sensitivities
    deck = plate_design.make_source(os.path.join(work, 'source'), size=0.6 if arguments.quick else 0.35, exact=exact)
    if arguments.validate:
        check = plate_design.PlateDesign(deck, os.path.join(work, 'validate'), variables=('x1', 'y1', 'r1', 'fillet'), exact=exact)
        print(plate_design.table(plate_design.validate(check, steps=(2e-3, 1e-3))))
        turn = plate_design.PlateDesign(deck, os.path.join(work, 'validate-turn'), variables=('turn',), exact=exact)
        print(plate_design.table(plate_design.validate(turn, steps=(0.1, 0.05))), flush=True)

    names = ('x1', 'r1', 'x2', 'r2', 'fillet')
    design = plate_design.PlateDesign(deck, work, variables=names, exact=exact)
    bounds = [(plate_design.VARIABLES[n]['lower'], plate_design.VARIABLES[n]['upper']) for n in names]
    start, gradients0, _ = design.evaluate(dict.fromkeys(names, 0.0), 'start')
    limit = 1.02 * start['TIP']
    history, cache = [], {}

    def evaluate(p):
        key = tuple(np.round(p, 12))
        if key not in cache:
            values = dict(zip(names, map(float, p)))
            J, dJdp, quality = design.evaluate(values, 'current')
            if quality['InvertedCells'] != 0:
                raise RuntimeError(f"the design {values} inverts {quality['InvertedCells']} elements")
            history.append(dict(values, mass=J['MASS'], tip=J['TIP'], MinScaledJacobian=quality['MinScaledJacobian']))
            print('run %2d: mass %.5g t, tip %.5g mm (limit %.5g), least scaled Jacobian %.3f, %s' % (
                len(history), J['MASS'], J['TIP'], limit, quality['MinScaledJacobian'],
                ', '.join('%s %+.3f' % (n, values[n]) for n in names)), flush=True)
            cache[key] = (J, dJdp)
        return cache[key]

    objective = lambda p: evaluate(p)[0]['MASS'] / start['MASS']  # noqa: E731
    objective_gradient = lambda p: np.array([evaluate(p)[1]['MASS'][n] for n in names]) / start['MASS']  # noqa: E731
    # the deflection bound as c(p) >= 0
    constraint = {'type': 'ineq', 'fun': lambda p: 1 - evaluate(p)[0]['TIP'] / limit,
                  'jac': lambda p: -np.array([evaluate(p)[1]['TIP'][n] for n in names]) / limit}
    result = minimize(objective, np.zeros(len(names)), jac=objective_gradient, bounds=bounds, constraints=[constraint],
                      method='SLSQP', options={'maxiter': 3 if arguments.quick else 30, 'ftol': 1e-4})
    # The best design is the lightest one run that meets the bound (the start does): SLSQP's last
    # iterate may lie outside it, as a quick run's few iterations leave it.
    J_last, _ = evaluate(result.x)
    feasible = [h for h in history if h['tip'] <= limit]
    chosen = min(feasible, key=lambda h: h['mass'])
    best = {n: chosen[n] for n in names}
    design.write(best, 'best')
    print('gradients: %s' % ('exact (mlsdeform.exactSensitivity)' if exact else "ccx's normal-only sensitivities"))
    print('SLSQP: %s after %d iterations, %d ccx runs; its last design: mass %.4g t, tip %.5g mm (limit %.5g)%s' % (
        result.message, result.nit, design.runs, J_last['MASS'], J_last['TIP'], limit,
        '' if J_last['TIP'] <= limit else ', beyond the limit by %.2g%%' % (100 * (J_last['TIP'] / limit - 1))))
    print('best design that meets the bound (run %d of %d): mass %.4g -> %.4g t (%+.1f%%), tip %.5g -> %.5g mm (limit %.5g): %s' % (
        history.index(chosen) + 1, len(history), start['MASS'], chosen['mass'], 100 * (chosen['mass'] / start['MASS'] - 1),
        start['TIP'], chosen['tip'], limit, ', '.join('%s %+.4f' % item for item in best.items())))

    # Why this is the answer: the gradients at the best design (the KKT conditions: the bound is
    # active, a variable at a bound may still lower the mass, a free one moves neither)
    _, gradients, _ = design.evaluate(best, 'kkt')
    print('at the best design: tip / limit %.6f; per variable dM/dp / M0, d(tip)/dp / limit:' % (chosen['tip'] / limit))
    for n, (lo, hi) in zip(names, bounds):
        where = 'at its upper bound' if abs(best[n] - hi) < 1e-6 else 'at its lower bound' if abs(best[n] - lo) < 1e-6 else 'free'
        print('  %-6s %+.4g, %+.4g (%s)' % (n, gradients['MASS'][n] / start['MASS'], gradients['TIP'][n] / limit, where))

    with open(os.path.join(work, 'history.csv'), 'w', newline='') as f:
        writer = csv.DictWriter(f, fieldnames=list(history[0]))
        writer.writeheader()
        writer.writerows(history)
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    figure, mass_axis = plt.subplots(figsize=(7, 3.8))
    runs = np.arange(1, len(history) + 1)
    mass_axis.plot(runs, [h['mass'] / start['MASS'] for h in history], 'o-', color='tab:blue', label='mass / start')
    mass_axis.set_xlabel('ccx run')
    mass_axis.set_ylabel('mass / start', color='tab:blue')
    tip_axis = mass_axis.twinx()
    tip_axis.plot(runs, [h['tip'] / start['TIP'] for h in history], 's--', color='tab:red', label='tip deflection / start')
    tip_axis.axhline(limit / start['TIP'], color='tab:red', linewidth=0.8, linestyle=':')
    tip_axis.set_ylabel('tip deflection / start (limit 1.02)', color='tab:red')
    figure.suptitle('Plate with holes: least mass with the tip deflection at most +2%% (SLSQP, CalculiX, %s)' % (
        'exact gradients' if exact else "ccx's sensitivities"), fontsize=10)
    figure.tight_layout()
    figure.savefig(os.path.join(work, 'optimize_plate.png'), dpi=100)
    return 0 if chosen['mass'] < start['MASS'] else 1   # a lighter design within the bound was found


if __name__ == '__main__':
    sys.exit(main())
