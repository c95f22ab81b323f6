"""Design sensitivities on the OpenFOAM hull case (run-sensitivity-benchmark.sh): reads CASE.foam
as mls_benchmark.py does, makes the hull a Handle with six design variables (translate x, y, z,
rotate about y and z, scale along x; mlsdeform.DesignVariables), the inlet and outlet Fixed and
the sides, bottom and top Slip, and times, RUNS times each (median):
  - a further variant: setDesignVars (new values) + update (the deformed points);
  - reverse mode: totalSensitivity(dJdX) with dJdX random on the hull patch's points, 0 elsewhere;
  - forward mode: one totalSensitivityProd per variable (m calls).
Prints a table with the ratios against the targets (reverse <= 20% of a further variant; forward
for m variables <= m times the further variant's solve, the filter's SolveTime: the
back-substitution and d = Phi w at the points, the stricter reading; against m whole further
variants too), a check that forward and reverse mode give the same
dJ/dp (exit code 1 when they differ by more than its bound), and one JSON line (SENSBENCH ...).
Usage: pvpython sensitivity_benchmark.py PLUGIN EXAMPLES_OPENFOAM_DIR CASE.foam RUNS [--set NAME=VALUE ...]
(--set: an MLS Deform property other than its default, e.g. MeshQuality=0)"""
import json
import os
import statistics
import sys
import time

import numpy as np
from paraview.simple import LoadPlugin
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet

plugin, examples, case, runs = sys.argv[1:5]
runs = int(runs)
settings = {}
arguments = iter(sys.argv[5:])
for argument in arguments:
    if argument != '--set':
        sys.exit('unknown argument %s' % argument)
    name, value = next(arguments).split('=', 1)
    settings[name] = float(value) if '.' in value or 'e' in value else int(value)
handle, fixed, slip = ['hull'], ['inlet', 'outlet'], ['sideYmin', 'sideYmax', 'bottom', 'top']
REVERSE_TARGET = 0.20  # reverse mode's time as a fraction of a further variant's
FORWARD_TARGET = 1.0   # forward mode's time for m variables as a fraction of m further variants' solves (SolveTime)
# Forward and reverse mode evaluate the same derivative, exactly or by the same GMRES tangents:
# they differ by rounding (and GMRES's tolerance), far below this relative bound.
AGREEMENT_BOUND = 1e-6

LoadPlugin(plugin, remote=False)
sys.path.insert(0, examples)
import mlsdeform  # noqa: E402  (the plugin's package: importable once the plugin is loaded)
import openfoam_variant  # noqa: E402
import hull_benchmark  # noqa: E402  (beside this script)
from hull_benchmark import timed  # noqa: E402


def patch_range(algorithm, patch):
    """(offset, count) of a patch's points in the MLS Deform output's order (mlsdeform's order:
    the leaves as a composite iterator visits them)."""
    output = algorithm.GetOutputDataObject(0)
    iterator = output.NewIterator()
    offset = 0
    iterator.InitTraversal()
    while not iterator.IsDoneWithTraversal():
        count = iterator.GetCurrentDataObject().GetNumberOfPoints()
        if iterator.GetCurrentMetaData().Get(vtkCompositeDataSet.NAME()) == patch:
            return offset, count
        offset += count
        iterator.GoToNextItem()
    raise RuntimeError('patch %s not found in the output' % patch)


def field_string(algorithm, name):
    array = algorithm.GetOutputDataObject(0).GetFieldData().GetAbstractArray(name)
    return array.GetValue(0) if array is not None else None


def field_number(algorithm, name):
    array = algorithm.GetOutputDataObject(0).GetFieldData().GetArray(name)
    return array.GetTuple1(0) if array is not None else None


# The case and its deformation with the hull at rest (the set-up), then the design variables.
t = time.perf_counter()
reader = openfoam_variant.open_case(case, handle + fixed + slip, decompose_polyhedra=False)
read_s = time.perf_counter() - t
t = time.perf_counter()
deformer = openfoam_variant.morph(reader, handle, (0, 0, 0), fixed, slip, **settings)
setup_s = time.perf_counter() - t
hull = deformer.Regions[0]  # morph() lists the handle regions first
dvs = mlsdeform.DesignVariables(deformer)
hull_benchmark.add_body_variables(dvs, hull)
names = dvs.getVarNames()
m = len(names)
first_s, X = timed(dvs.update)
algorithm = deformer.GetClientSideObject()
offset, count = patch_range(algorithm, 'hull')
dJdX = np.zeros_like(X)
dJdX[offset:offset + count] = np.random.default_rng(1).standard_normal((count, 3))


def further_variant(run):
    """A further variant: every variable moved (up to 0.1 m, 1 degree, 2%), differently in each run."""
    s = (1 if run % 2 == 0 else -1) * (run + 1) / runs
    dvs.setDesignVars({'tx': 0.1 * s, 'ty': 0.02 * s, 'tz': 0.05 * s, 'ry': 0.5 * s, 'rz': 1.0 * s, 'sx': 0.02 * s})
    return dvs.update()


further, solve, reverse, forward, agreement = [], [], [], [], []
for run in range(runs):
    seconds, _ = timed(lambda: further_variant(run))
    further.append(seconds)
    solve.append(field_number(algorithm, 'SolveTime'))
    seconds, dJdp = timed(lambda: dvs.totalSensitivity(dJdX))
    reverse.append(seconds)
    seconds, dXdp = timed(lambda: [dvs.totalSensitivityProd({name: 1.0}) for name in names])
    forward.append(seconds)
    # the check: dJ/dp from the forward mode's dX/dp against the reverse mode's
    from_forward = np.array([np.sum(dJdX * d) for d in dXdp])
    from_reverse = np.array([dJdp[name] for name in names])
    agreement.append(float(np.max(np.abs(from_forward - from_reverse)) / np.max(np.abs(from_reverse))))

output_info = deformer.GetDataInformation()
result = {
    'case': case, 'threads': os.environ.get('OMP_NUM_THREADS', 'unset'), 'runs': runs, 'settings': settings,
    'vtk_points': output_info.GetNumberOfPoints(), 'vtk_cells': output_info.GetNumberOfCells(),
    'hull_points': count, 'variables': names, 'method': field_string(algorithm, 'SensitivityMethod'),
    'read_s': read_s, 'setup_s': setup_s, 'first_update_s': first_s,
    'further_s': further, 'solve_s': solve, 'reverse_s': reverse, 'forward_s': forward, 'agreement': agreement,
    'peak_mib': next(int(line.split()[1]) / 1024.0 for line in open('/proc/self/status') if line.startswith('VmHWM:')),
}
median = {key: statistics.median(result[key]) for key in ('further_s', 'solve_s', 'reverse_s', 'forward_s')}
reverse_ratio = median['reverse_s'] / median['further_s']
forward_ratio = median['forward_s'] / (m * median['solve_s'])
forward_variants = median['forward_s'] / (m * median['further_s'])
result.update(reverse_ratio=reverse_ratio, forward_ratio=forward_ratio, forward_of_variants=forward_variants)

print('Sensitivity benchmark: %s, %d points and %d cells (the VTK output), hull patch %d points, %d design variables '
      '(%s), OMP_NUM_THREADS=%s, medians of %d runs' % (case, result['vtk_points'], result['vtk_cells'], count, m,
                                                       ', '.join(names), result['threads'], runs))
print('set-up (read %.2f s, deform %.2f s, first update with the variables %.2f s), peak memory %.0f MiB'
      % (read_s, setup_s, first_s, result['peak_mib']))
print('SensitivityMethod: %s' % result['method'])
print('| %-48s | %10s | %-32s | %-34s |' % ('operation', 'median', 'runs [s]', 'ratio (target)'))
print('| %-48s | %8.3f s | %-32s | %-34s |' % ('further variant (setDesignVars + update)', median['further_s'],
                                                 ' '.join('%.3f' % s for s in further), 'solve (SolveTime) %.3f s' % median['solve_s']))
print('| %-48s | %8.3f s | %-32s | %-34s |' % ('reverse mode: dJ/dp of all %d (totalSensitivity)' % m, median['reverse_s'],
                                                 ' '.join('%.3f' % s for s in reverse),
                                                 '%.3f of a variant (<= %.2f) %s' % (reverse_ratio, REVERSE_TARGET,
                                                                                     'met' if reverse_ratio <= REVERSE_TARGET else 'NOT MET')))
print('| %-48s | %8.3f s | %-32s | %-34s |' % ('forward mode: %d totalSensitivityProd' % m, median['forward_s'],
                                                 ' '.join('%.3f' % s for s in forward),
                                                 '%.2f of %d solves (<= %.2f) %s' % (forward_ratio, m, FORWARD_TARGET,
                                                                                    'met' if forward_ratio <= FORWARD_TARGET else 'NOT MET')))
print('  (forward mode: %.3f of %d whole further variants)' % (forward_variants, m))
worst = max(agreement)
print('check: dJ/dp by forward and reverse mode, largest relative difference %.2e (bound %.0e): %s'
      % (worst, AGREEMENT_BOUND, 'agree' if worst <= AGREEMENT_BOUND else 'DISAGREE'))
print('SENSBENCH ' + json.dumps(result))
sys.exit(0 if worst <= AGREEMENT_BOUND else 1)
