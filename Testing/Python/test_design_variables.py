"""Issue 29: the Python interface of design variables (mlsdeform.DesignVariables), in pvpython,
from a state file and split over MPI ranks.

  pvpython test_design_variables.py PLUGIN WORK serial
      writes WORK/scene.vtm (a sphere's surface inside a tetrahedral box, one block each), checks
      the interface (definition, values, update, forward and reverse mode, checkDerivatives, bad
      input, a saved and loaded state) and writes the serial results to WORK/reference.npz;
  mpiexec -n N pvbatch --symmetric test_design_variables.py PLUGIN WORK ranks
      every rank runs the script on its piece (RedistributeDataSet): dJ/dp equals the serial one
      bitwise and each point's dX/dp the serial one at the same position.
"""
import os
import sys

import numpy as np
import paraview.simple as pvs
from paraview.simple import LoadPlugin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sphere_in_box  # noqa: E402

plugin, work, mode = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
import mlsdeform  # noqa: E402  (importable once the plugin is loaded)

failures = []


def check(condition, what):
    if mode == 'serial' or rank == 0:
        print(('ok   ' if condition else 'FAIL ') + what, flush=True)
    if not condition:
        failures.append(what)


def raises(exception, call, what):
    try:
        call()
    except exception as e:
        check(True, '%s: %s' % (what, e))
        return
    check(False, '%s raises %s' % (what, exception.__name__))


def box_region(source, role, bounds, **properties):
    return sphere_in_box.box_region(ConstraintRegion, source, role, bounds, **properties)  # noqa: F821



def scene(source):
    """A sphere (two Handles: its upper and lower half) in a box whose sides are Fixed and whose
    floor slips, with a translation, a rotation and a scale variable and one spreading the halves."""
    upper = box_region(source, 'Handle', [-0.35, 0.35, -0.35, 0.35, 0.0, 0.35], Translation=[0.02, 0, 0])
    lower = box_region(source, 'Handle', [-0.35, 0.35, -0.35, 0.35, -0.35, -0.001])
    fixed = ConstraintRegion(Input=source, Role='Fixed', InsideOut=1)
    fixed.Region = 'Box'
    fixed.Region.UseReferenceBounds = 0
    fixed.Region.Position = [-0.99, -0.99, -1.01]
    fixed.Region.Length = [1.98, 1.98, 2.0]
    floor = box_region(source, 'Slip', [-0.99, 0.99, -0.99, 0.99, -1.01, -0.99])
    deform = MLSDeform(Input=source, Regions=[upper, lower, fixed, floor], NumberOfSamples=300)
    dvs = mlsdeform.DesignVariables(deform)
    dvs.addHandleDV('lift', upper, translate=[0, 0, 1], lower=-0.05, upper=0.05)
    dvs.addHandleDV('twist', upper, rotate=[0, 0, 1], lower=-5, upper=5)
    dvs.addHandleDV('stretch', upper, scale=[1, 0, 0], lower=-0.1, upper=0.1)
    dvs.addHandleDV('spread', [upper, lower], translate=[[0, 0, 1], [0, 0, -1]], lower=0, upper=0.02)
    values = {'lift': 0.01, 'twist': 2.0, 'stretch': 0.05, 'spread': 0.01}
    dvs.setDesignVars(values)
    return deform, dvs, values, (upper, lower, fixed, floor)


def gradient(rest):
    """A dJ/dX that depends on the position only (the same on any rank): non-zero near the sphere."""
    g = np.stack([np.sin(3 * rest[:, 0]), np.cos(2 * rest[:, 1]), rest[:, 2]], axis=1)
    g[np.linalg.norm(rest, axis=1) > 0.5] = 0
    return g


if mode == 'serial':
    rank = 0
    os.makedirs(work, exist_ok=True)
    path = os.path.join(work, 'scene.vtm')
    sphere_in_box.write_scene(path, 10)
    source = pvs.OpenDataFile(path)
    deform, dvs, values, (upper, lower, fixed, floor) = scene(source)
    check(dvs.getVarNames() == ['lift', 'twist', 'stretch', 'spread'] and dvs.getNDV() == 4, 'four variables, in order')
    check(dvs.getValues() == values, 'getValues: the values set')
    check(dvs.getBounds()['spread'] == (0, 0.02), 'getBounds: (lower, upper)')
    X = dvs.update()
    rest = sphere_in_box.rest_points(deform)
    check(X.dtype == np.float64 and X.shape == rest.shape, 'update() returns (n, 3) doubles in output order (%s)' % (X.shape,))
    algorithm = deform.GetClientSideObject()
    samplings = algorithm.GetNumberOfSamplings()
    dvs.setDesignVars({'lift': 0.02})
    X2 = dvs.update()
    check(algorithm.GetNumberOfSamplings() == samplings and algorithm.GetNumberOfFactorizations() == 1,
          'setDesignVars moves the handles only: the set-up stays cached')
    check(np.abs(X2 - X).max() > 0.009, 'a new value moves the model')
    dvs.setDesignVars({'lift': 0.01})
    check(np.array_equal(dvs.update(), X), 'the same values give the same points bitwise')
    # forward and reverse mode: sum_i g_i . dX_i/dp = dJ/dp, round-off apart (a few eps of sum |g . dX/dp|)
    g = gradient(rest)
    dJdp = dvs.totalSensitivity(g)
    forward = {}
    for name in dvs.getVarNames():
        dX = dvs.totalSensitivityProd({name: 1.0})
        forward[name] = dX
        products = (g * dX).sum(axis=1)
        check(abs(dJdp[name] - products.sum()) <= 1e-12 * np.abs(products).sum(),
              'reverse %s = %.15g, forward %.15g' % (name, dJdp[name], products.sum()))
    combined = dvs.totalSensitivityProd({'lift': 1.0, 'twist': 0.5})
    check(np.abs(combined - forward['lift'] - 0.5 * forward['twist']).max() <= 1e-12 * np.abs(combined).max(),
          'totalSensitivityProd of a combination is the combination of the products')
    # the spread variable moves the two halves apart: +z on the upper, -z on the lower (the
    # halves abut with opposite targets, so the penalty's compromise at the equator keeps them
    # short of +-1 there: the sign and the larger part of the motion are asserted)
    spread = forward['spread']
    on_sphere = np.abs(np.linalg.norm(rest, axis=1) - 0.3) < 1e-6
    upper_half, lower_half = on_sphere & (rest[:, 2] > 0.01), on_sphere & (rest[:, 2] < -0.01)
    check(spread[upper_half, 2].mean() > 0.5 and spread[lower_half, 2].mean() < -0.5,
          'spread: dX/dp = +z on the upper half (mean %.4f), -z on the lower (%.4f)'
          % (spread[upper_half, 2].mean(), spread[lower_half, 2].mean()))
    # checkDerivatives: translation and scale act linearly (the difference is exact up to the
    # output's round-off, 1e-14 over the step 1e-4: 1e-10), a rotation's truncation is
    # (h pi/180)^2 / 6 = 5e-13: the 1e-6 holds
    worst = dvs.checkDerivatives(step=1e-4)
    check(worst <= 1e-6, 'checkDerivatives: largest relative difference %.3g <= 1e-6' % worst)
    check(dvs.getValues() == values, 'checkDerivatives restores the values')

    # bad input: a ValueError (or RuntimeError from the filter) and nothing changed
    before = [list(r.DesignVariables) for r in (upper, lower, fixed)]
    raises(ValueError, lambda: dvs.addHandleDV('x', fixed, translate=[1, 0, 0], lower=-1, upper=1), 'a variable on a Fixed region')
    raises(ValueError, lambda: dvs.addHandleDV('x', upper, translate=[0, 0, 0], lower=-1, upper=1), 'a zero axis')
    raises(ValueError, lambda: dvs.addHandleDV('lift', upper, translate=[1, 0, 0], lower=-1, upper=1), 'a duplicate name')
    raises(ValueError, lambda: dvs.addHandleDV('x', upper, translate=[1, 0, 0], lower=1, upper=-1), 'lower > upper')
    raises(ValueError, lambda: dvs.addHandleDV('x', upper, translate=[1, 0, 0], lower=0, upper=1, value=2), 'a start value outside the bounds')
    raises(ValueError, lambda: dvs.addHandleDV('x', upper, translate=[1, 0, 0], rotate=[1, 0, 0], lower=0, upper=1), 'two kinds at once')
    raises(ValueError, lambda: dvs.setDesignVars({'lift': 0.5}), 'a value outside its bounds')
    raises(ValueError, lambda: dvs.setDesignVars({'lift': 0.0, 'drag': 1.0}), 'an unknown variable')
    raises(ValueError, lambda: dvs.totalSensitivity(g[:-1]), 'dJ/dX of the wrong size')
    raises(ValueError, lambda: dvs.totalSensitivity(g[:, :2]), 'dJ/dX with 2 components')
    nan = g.copy()
    nan[0, 0] = np.nan
    raises(ValueError, lambda: dvs.totalSensitivity(nan), 'NaN in dJ/dX')
    check([list(r.DesignVariables) for r in (upper, lower, fixed)] == before and dvs.getValues() == values,
          'the failed calls changed nothing')
    # a bad variable set on the property directly: the filter's message as a RuntimeError
    upper.DesignVariables = list(upper.DesignVariables) + ['bad', '0', '0', '0', '0', '0', '-1', '1']
    try:
        dvs.update()
        check(False, 'a zero axis set on the property raises RuntimeError')
    except RuntimeError as e:
        check('non-zero, finite axis' in str(e), "a zero axis set on the property: the region's message (%s)" % e)
    upper.DesignVariables = before[0]
    check(np.array_equal(dvs.update(), X), 'after the bad property is removed the deformation is the same again')

    # the same design in a 2D deformation extruded along z (the scene is not 2D: this only gives the
    # ranks a reference for ExtrusionAxis's projected rows and slide)
    deform.ExtrusionAxis = 'Z'
    extrusion = {'X': dvs.update(), 'dJdp': np.array(list(dvs.totalSensitivity(g).values()))}
    extrusion.update({'dX_' + n: dvs.totalSensitivityProd({n: 1.0}) for n in dvs.getVarNames()})
    deform.ExtrusionAxis = 'None'
    check(np.all(extrusion['X'][:, 2] == rest[:, 2]), 'extruded along z: no point moves along z')

    # a state file keeps the variables: DesignVariables of the loaded filter finds them
    restored = mlsdeform.DesignVariables(sphere_in_box.reloaded(os.path.join(work, 'state.pvsm'), plugin, globals()))
    check(restored.getVarNames() == ['lift', 'twist', 'stretch', 'spread'] and restored.getValues() == values
          and restored.getBounds()['twist'] == (-5, 5), 'a loaded state restores the variables (%s)' % restored.getValues())
    check(np.array_equal(restored.update(), X), 'and the loaded state deforms the same, bitwise')
    np.savez(os.path.join(work, 'reference.npz'), rest=rest, X=X, g=g,
             dJdp=np.array([dJdp[n] for n in dvs.getVarNames()]), **{'dX_' + n: forward[n] for n in forward},
             **{'extruded_' + k: v for k, v in extrusion.items()})
else:
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    controller = vtkMultiProcessController.GetGlobalController()
    rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    reference = np.load(os.path.join(work, 'reference.npz'))
    source = pvs.RedistributeDataSet(Input=pvs.OpenDataFile(os.path.join(work, 'scene.vtm')))
    deform, dvs, values, _ = scene(source)
    X = dvs.update()
    rest = sphere_in_box.rest_points(deform)
    index = {tuple(x): i for i, x in enumerate(reference['rest'])}
    which = np.array([index.get(tuple(x), -1) for x in rest], dtype=int)
    check((which >= 0).all(), 'rank %d: each of its %d points is a point of the scene' % (rank, len(rest)))
    # dJ/dp: the same doubles as the serial run on every rank, although the pieces share points
    dJdp = dvs.totalSensitivity(gradient(rest))
    mine = np.array([dJdp[n] for n in dvs.getVarNames()])
    check(np.array_equal(mine, reference['dJdp']), 'rank %d of %d: dJ/dp %s equals the serial %s bitwise'
          % (rank, ranks, mine.tolist(), reference['dJdp'].tolist()))
    for name in dvs.getVarNames():
        dX = dvs.totalSensitivityProd({name: 1.0})
        serial = reference['dX_' + name][which]
        check(np.array_equal(dX, serial), 'rank %d: dX/d%s at its points equals the serial one bitwise (largest difference %g)'
              % (rank, name, np.abs(dX - serial).max() if len(dX) else 0))
    check(np.array_equal(X, reference['X'][which]), 'rank %d: the points equal the serial ones bitwise' % rank)
    # extruded along z: the mid-plane is the whole input's, so the ranks' projections are the serial ones
    deform.ExtrusionAxis = 'Z'
    check(np.array_equal(dvs.update(), reference['extruded_X'][which]), 'rank %d: extruded, the points equal the serial ones bitwise' % rank)
    dJdp = dvs.totalSensitivity(gradient(rest))
    check(np.array_equal(np.array(list(dJdp.values())), reference['extruded_dJdp']), 'rank %d: extruded, dJ/dp is the serial one bitwise' % rank)
    for name in dvs.getVarNames():
        check(np.array_equal(dvs.totalSensitivityProd({name: 1.0}), reference['extruded_dX_' + name][which]),
              'rank %d: extruded, dX/d%s is the serial one bitwise' % (rank, name))

if failures:
    print('%d check(s) failed' % len(failures))
    sys.exit(1)
