"""Constraint functions with many local variables on the OpenFOAM hull case
(run-constraint-benchmark.sh; issue 66 point 3): reads CASE.foam as sensitivity_benchmark.py does,
gives the hull VARIABLES local variables (DesignVariables.addLocalDV, count=VARIABLES; or, with
VARIABLES = 6, the sensitivity benchmark's six body variables and no constraints: today's memory
baseline) and the constraints of an optimization (mlsdeform.DesignConstraints): 10 beam thicknesses
along the hull, the volume it encloses, its area, 10 linear relations; and, on their own, the KS
non-orthogonality and the KS skewness of the mesh. Times, RUNS times each (median):
  - a further variant (setDesignVars + update);
  - reverse mode: dJ/dp of every variable (totalSensitivity, dJ/dX random on the hull's points);
  - the geometric constraints' values and gradients (evalFunctions + evalFunctionsSens);
  - the mesh-quality functions with their gradients (the non-orthogonality over the interior
    faces; the skewness over the interior and boundary faces);
and prints a table with the ratios against the targets (dJ/dp plus every constraint's gradient
<= 0.5 of a variant; the mesh quality with its gradient <= 1 variant), the peak memory and one
JSON line (CONSBENCH ...).
Usage: pvpython constraint_benchmark.py PLUGIN EXAMPLES_OPENFOAM_DIR CASE.foam RUNS VARIABLES"""
import json
import os
import statistics
import sys
import time

import numpy as np
from paraview.simple import LoadPlugin

plugin, examples, case, runs, variables = sys.argv[1:6]
runs, variables = int(runs), int(variables)
handle, fixed, slip = ['hull'], ['inlet', 'outlet'], ['sideYmin', 'sideYmax', 'bottom', 'top']
GRADIENTS_TARGET = 0.5  # dJ/dp and every constraint's gradient, as a fraction of a further variant
QUALITY_TARGET = 1.0    # the mesh-quality function with its gradient, as a fraction of a further variant

LoadPlugin(plugin, remote=False)
sys.path.insert(0, examples)
import mlsdeform  # noqa: E402
import openfoam_variant  # noqa: E402
import hull_benchmark  # noqa: E402  (beside this script)
from hull_benchmark import timed  # noqa: E402


t = time.perf_counter()
reader = openfoam_variant.open_case(case, handle + fixed + slip, decompose_polyhedra=False)
deformer = openfoam_variant.morph(reader, handle, (0, 0, 0), fixed, slip)
setup_s = time.perf_counter() - t
hull = deformer.Regions[0]
dvs = mlsdeform.DesignVariables(deformer)
if variables == 6:
    hull_benchmark.add_body_variables(dvs, hull)
else:
    dvs.addLocalDV('hull', hull, count=variables, lower=-0.02, upper=0.02)  # metres along the normal
names = dvs.getVarNames()
first_s, X = timed(dvs.update)
# dJ/dX random on the hull's points: the hull patch's polygons' corners
hull_points = np.unique(mlsdeform.constraints._Surface(deformer.GetClientSideObject().GetOutputDataObject(0), 'hull', 'hull').triangles)
dJdX = np.zeros_like(X)
dJdX[hull_points] = np.random.default_rng(1).standard_normal((len(hull_points), 3))

constraints_s = 0.0
if variables != 6:
    t = time.perf_counter()
    cons = mlsdeform.DesignConstraints(dvs)
    lo, hi = X[hull_points].min(axis=0), X[hull_points].max(axis=0)
    length, draft = hi[0] - lo[0], 0.5 * (lo[2] + hi[2])
    cons.addThicknessConstraints1D('beam', [[lo[0] + 0.1 * length, 0, draft], [hi[0] - 0.1 * length, 0, draft]], 10, [0, 1, 0],
                                   surface='hull', lower=0.95)
    cons.addTriangulatedVolumeConstraint('volume', surface='hull', lower=1.0)
    cons.addSurfaceAreaConstraint('area', surface='hull', upper=1.05)
    cons.addLinearConstraintsShape('linear', names[0:20:2], names[1:20:2], 1.0, -1.0, lower=-0.01, upper=0.01)
    cons.addMeshVolumeConstraint('fluid', lower=0.99)   # the volume mesh's (the fluid's, outside the hull)
    quality = mlsdeform.DesignConstraints(dvs)
    quality.addMeshQualityConstraint('nonOrtho', 'nonOrthogonality', upper=70)
    constraints_s = time.perf_counter() - t

further, reverse, gradients, mesh, skew = [], [], [], [], []
rng = np.random.default_rng(2)
for run in range(runs):
    values = dict(zip(names, (rng.uniform(-0.01, 0.01, len(names)) if variables != 6 else
                              np.array([0.1, 0.02, 0.05, 0.5, 1.0, 0.02]) * (run + 1) / runs) * (1 if run % 2 == 0 else -1)))
    seconds, _ = timed(lambda: (dvs.setDesignVars(values), dvs.update()))
    further.append(seconds)
    seconds, _ = timed(lambda: dvs.totalSensitivity(dJdX))
    reverse.append(seconds)
    if variables != 6:
        seconds, _ = timed(lambda: (cons.evalFunctions({}), cons.evalFunctionsSens({})))
        gradients.append(seconds)
        seconds, _ = timed(lambda: (quality.evalFunctions({}), quality.evalFunctionsSens({})))
        mesh.append(seconds)

peak_mib = next(int(line.split()[1]) / 1024.0 for line in open('/proc/self/status') if line.startswith('VmHWM:'))
if variables != 6:
    # the KS skewness on its own, after the peak memory of the constraints above is taken (its
    # point set and buffers are a third DesignConstraints'): a new design each run, as above
    skewness = mlsdeform.DesignConstraints(dvs)
    skewness.addMeshQualityConstraint('skew', 'skewness', upper=4)
    for run in range(runs):
        dvs.setDesignVars(dict(zip(names, rng.uniform(-0.01, 0.01, len(names)))))
        dvs.update()
        seconds, _ = timed(lambda: (skewness.evalFunctions({}), skewness.evalFunctionsSens({})))
        skew.append(seconds)

info = deformer.GetDataInformation()
result = {
    'case': case, 'threads': os.environ.get('OMP_NUM_THREADS', 'unset'), 'runs': runs, 'variables': len(names),
    'vtk_points': info.GetNumberOfPoints(), 'vtk_cells': info.GetNumberOfCells(), 'hull_points': int(len(hull_points)),
    'setup_s': setup_s, 'first_update_s': first_s, 'constraints_setup_s': constraints_s,
    'further_s': further, 'reverse_s': reverse, 'constraints_s': gradients, 'mesh_quality_s': mesh, 'skewness_s': skew,
    'cpu': next((line.split(':', 1)[1].strip() for line in open('/proc/cpuinfo') if line.startswith('model name')), '?'),
    'peak_mib': peak_mib,
}
median = {k: statistics.median(result[k]) if result[k] else None for k in ('further_s', 'reverse_s', 'constraints_s', 'mesh_quality_s', 'skewness_s')}
print('Constraint benchmark: %s, %d points and %d cells, hull %d points, %d design variables, OMP_NUM_THREADS=%s, '
      'medians of %d runs, %s' % (case, result['vtk_points'], result['vtk_cells'], len(hull_points), len(names),
                                  result['threads'], runs, result['cpu']))
print('set-up (read + deform %.2f s, first update %.2f s, constraints added %.2f s), peak memory %.0f MiB'
      % (setup_s, first_s, constraints_s, result['peak_mib']))
print('| %-58s | %10s | %-40s |' % ('operation', 'median', 'ratio (target)'))
print('| %-58s | %8.3f s | %-40s |' % ('further variant (setDesignVars + update)', median['further_s'], ''))
print('| %-58s | %8.3f s | %-40s |' % ('reverse mode: dJ/dp of all %d (totalSensitivity)' % len(names), median['reverse_s'],
                                        '%.2f of a variant' % (median['reverse_s'] / median['further_s'])))
if variables != 6:
    both = median['reverse_s'] + median['constraints_s']
    ratio, quality_ratio = both / median['further_s'], median['mesh_quality_s'] / median['further_s']
    result.update(gradients_ratio=ratio, quality_ratio=quality_ratio)
    print('| %-58s | %8.3f s | %-40s |' % ('geometric constraints (%d values): evalFunctions + Sens' % sum(
        len(np.atleast_1d(c.baseline)) for c in cons._constraints.values()), median['constraints_s'], ''))
    print('| %-58s | %8.3f s | %-40s |' % ('dJ/dp + every constraint\'s gradient', both, '%.2f of a variant (<= %.1f) %s' % (
        ratio, GRADIENTS_TARGET, 'met' if ratio <= GRADIENTS_TARGET else 'NOT MET')))
    print('| %-58s | %8.3f s | %-40s |' % ('mesh quality (KS non-orthogonality) with its gradient', median['mesh_quality_s'],
                                            '%.2f of a variant (<= %.1f) %s' % (quality_ratio, QUALITY_TARGET,
                                                                               'met' if quality_ratio <= QUALITY_TARGET else 'NOT MET')))
    skew_ratio = median['skewness_s'] / median['further_s']
    result.update(skewness_ratio=skew_ratio)
    print('| %-58s | %8.3f s | %-40s |' % ('mesh quality (KS skewness) with its gradient', median['skewness_s'],
                                            '%.2f of a variant (<= %.1f) %s' % (skew_ratio, QUALITY_TARGET,
                                                                               'met' if skew_ratio <= QUALITY_TARGET else 'NOT MET')))
print('CONSBENCH ' + json.dumps(result))
