"""Issue 66 point 1: local shape variables (DesignVariables.addLocalDV), in pvpython and split over
MPI ranks.

  pvpython test_local_variables.py PLUGIN WORK serial
      the sphere in a box (sphere_in_box.py) with 12 control points on the sphere (its outward
      normals) and a mirrored pair along a given direction, and an extruded slab whose top face
      has control lines through its thickness: p = 0 leaves every point in place, a control point
      moves by exactly p a, the bump is smooth and local, Fixed and Slip hold, forward and reverse
      mode agree, central differences with h and h/2 agree with the exact dX/dp, bad input raises
      ValueError and changes nothing, a saved state keeps the variables; writes WORK/local.npz;
  mpiexec -n N pvbatch --symmetric test_local_variables.py PLUGIN WORK ranks
      each rank's dX/dp and dJ/dp equal the serial ones bitwise (the control points, their normals
      and the deformation do not depend on the split).
"""
import os
import sys

import numpy as np
import paraview.simple as pvs
from paraview.simple import LoadPlugin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sphere_in_box  # noqa: E402
from checks import check, finish, raises  # noqa: E402

plugin, work, mode = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
import mlsdeform  # noqa: E402  (importable once the plugin is loaded)

def scene(source):
    return sphere_in_box.local_scene(globals(), source)


def slab_scene(path, quadratic=False, direction='normal'):
    """A one-cell-thick slab [0, 1] x [0, 0.5] x [0, 0.1] of tetrahedra (quadratic ones: a deck's
    C3D10) deformed as a 2D case (ExtrusionAxis Z): its top face (y = 0.5) the Handle of 4 control
    lines along z (moving along direction), its floor Fixed, its front and back slipping."""
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
    from vtkmodules.vtkFiltersGeometry import vtkLinearToQuadraticCellsFilter
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
    image = vtkImageData()
    image.SetDimensions(11, 6, 2)
    image.SetSpacing(0.1, 0.1, 0.1)
    tets = vtkDataSetTriangleFilter()
    tets.SetInputData(image)
    cells = tets
    if quadratic:
        cells = vtkLinearToQuadraticCellsFilter()
        cells.SetInputConnection(tets.GetOutputPort())
        cells.SetOutputPointsPrecision(1)  # doubles, as a deck's nodes
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(cells.GetOutputPort())
    writer.Write()
    source = pvs.OpenDataFile(path)
    box = lambda role, bounds: sphere_in_box.box_region(ConstraintRegion, source, role, bounds)  # noqa: E731,F821
    top = box('Handle', [-0.01, 1.01, 0.49, 0.51, -0.01, 0.11])
    regions = [top, box('Fixed', [-0.01, 1.01, -0.01, 0.01, -0.01, 0.11]), box('Slip', [-0.01, 1.01, -0.01, 0.51, -0.01, 0.01]),
               box('Slip', [-0.01, 1.01, -0.01, 0.51, 0.09, 0.11])]
    deform = MLSDeform(Input=source, Regions=regions, NumberOfSamples=60, ExtrusionAxis='Z')  # noqa: F821  (a 2D case)
    dvs = mlsdeform.DesignVariables(deform)
    lines = dvs.addLocalDV('top', top, count=4, axis=[0, 0, 1], direction=direction, lower=-0.05, upper=0.05)
    return deform, dvs, lines, top


def gradient(rest):
    """A dJ/dX that depends on the position only (the same on any rank)."""
    return np.stack([np.sin(3 * rest[:, 0]), np.cos(2 * rest[:, 1]), rest[:, 2] + 0.5], axis=1)


def at(rest, x):
    return int(np.argmin(np.linalg.norm(rest - x, axis=1)))


if mode == 'serial':
    os.makedirs(work, exist_ok=True)
    path = os.path.join(work, 'scene.vtm')
    sphere_in_box.write_scene(path, 10)
    source = pvs.OpenDataFile(path)
    deform, dvs, bumps, pair, (body, fixed, floor, side) = scene(source)
    check(bumps == ['bump_%d' % i for i in range(12)] and pair == ['pair_0'] and dvs.getNDV() == 13,
          'addLocalDV: one variable a control point, named name_i (%s)' % (bumps + pair))
    check(dvs.getBounds()['bump_3'] == (-0.05, 0.05) and all(v == 0 for v in dvs.getValues().values()), 'bounds given, values 0')
    rest = sphere_in_box.rest_points(deform)
    X0 = dvs.update()
    check(np.abs(X0 - rest).max() <= 1e-12, 'at p = 0 every point stays put (largest motion %.2g)' % np.abs(X0 - rest).max())
    controls = dvs.getControlPoints()
    on_sphere = np.abs(np.linalg.norm(rest, axis=1) - 0.3) < 1e-6
    x0, n0 = controls['bump_0'][0][0], controls['bump_0'][1][0]
    spacing = min(np.linalg.norm(controls[b][0][0] - x0) for b in bumps[1:])
    check(abs(np.linalg.norm(x0) - 0.3) < 1e-6 and np.dot(n0, x0 / 0.3) > 0.99 and abs(np.linalg.norm(n0) - 1) < 1e-12,
          'a control point lies on the sphere with the outward unit normal (n . x/|x| = %.4f); spacing %.3f'
          % (np.dot(n0, x0 / 0.3), spacing))
    # spread evenly: farthest-point sampling takes each control point farthest from those before
    # it, so they are at least as far apart as any sphere point is from its nearest one
    held = np.array([controls[b][0][0] for b in bumps])
    covering = np.linalg.norm(rest[on_sphere][:, None] - held[None], axis=2).min(axis=1).max()
    apart = min(np.linalg.norm(held[i] - held[j]) for i in range(len(held)) for j in range(i))
    check(apart >= covering - 1e-12 and covering < 0.3, 'the 12 control points are %.3f apart at least, every sphere point within '
          '%.3f of one (the covering radius, below the sphere\'s 0.3)' % (apart, covering))
    p = 0.02
    dvs.setDesignVars({'bump_0': p})
    X = dvs.update()
    motion = np.linalg.norm(X - rest, axis=1)
    i0 = at(rest, x0)
    check(np.linalg.norm(X[i0] - rest[i0] - p * n0) <= 1e-9 * p, 'the control point moves by exactly p n (error %.2g)'
          % np.linalg.norm(X[i0] - rest[i0] - p * n0))
    others = [at(rest, controls[b][0][0]) for b in bumps[1:]]
    check(motion[others].max() <= 1e-9 * p, 'the other control points stay put (largest %.2g)' % motion[others].max())
    distance = np.linalg.norm(rest - x0, axis=1)
    edge = distance[on_sphere & (distance > 0)].min()  # the nearest sphere point: one edge away
    near = on_sphere & (distance > 0) & (distance < 1.5 * edge)
    far = on_sphere & (distance > 2 * spacing)
    check(near.any() and motion[near].min() >= 0.5 * p, 'smooth, no step: the %d sphere points next to it move %.0f-%.0f%% of p'
          % (near.sum(), 100 * motion[near].min() / p, 100 * motion[near].max() / p))
    check(far.any() and motion[far].max() <= 0.05 * p, 'local: beyond two spacings the sphere moves at most %.1f%% of p'
          % (100 * motion[far].max() / p))
    fixed_points = np.max(np.abs(rest[:, :2]), axis=1) >= 0.99
    check(np.abs(X[fixed_points] - rest[fixed_points]).max() == 0, 'the Fixed sides stay exactly')
    # the mirrored pair: +y at (0.2, 0.6, 0.2), the image (-0.2, 0.6, 0.2) along the mirrored +y
    dvs.setDesignVars({'bump_0': 0.0, 'pair_0': 0.05})
    X = dvs.update()
    a, b = at(rest, [0.2, 0.6, 0.2]), at(rest, [-0.2, 0.6, 0.2])
    check(np.linalg.norm(X[a] - rest[a] - [0, 0.05, 0]) <= 1e-9 and np.linalg.norm(X[b] - rest[b] - [0, 0.05, 0]) <= 1e-9,
          'a mirrored pair shares its variable: both points move by p (0, 1, 0) (mirrored across x = 0)')
    check(len(dvs.getControlPoints('pair_0')['pair_0'][0]) == 2, 'the pair has two control points')
    values = dict(dvs.getValues(), bump_0=0.02, bump_5=-0.03, pair_0=0.04)
    dvs.setDesignVars(values)
    X = dvs.update()

    # forward and reverse mode agree; central differences with h and h/2 agree with the exact dX/dp:
    # the map is linear in p, so the differences are exact up to the output's round-off (1e-15
    # over h = 1e-3: 1e-12 relative)
    g = gradient(rest)
    dJdp = dvs.totalSensitivity(g)
    forward = {n: dvs.totalSensitivityProd({n: 1.0}) for n in dvs.getVarNames()}
    worst = max(abs(dJdp[n] - (g * forward[n]).sum()) / np.abs(g * forward[n]).sum() for n in dvs.getVarNames())
    check(worst <= 1e-12, 'reverse mode (one back-substitution) equals the forward products (largest relative difference %.2g)' % worst)
    for h in (1e-3, 5e-4):
        worst = dvs.checkDerivatives(step=h, verbose=False)
        check(worst <= 1e-9, 'central differences with h = %g agree with dX/dp of all 13 variables (largest relative %.2g)' % (h, worst))
    check(dvs.getValues() == values, 'checkDerivatives restores the values')

    # bad input: a ValueError and nothing changed
    rows = [(list(r.DesignVariables), list(r.ControlPoints)) for r in (body, side)]
    names = dvs.getVarNames()
    raises(lambda: dvs.addLocalDV('many', body, count=400), 'only 338 points', 'more control points than the region has points')
    raises(lambda: dvs.addLocalDV('z', body, count=2, direction=[0, 0, 0]), 'must not be zero', 'a zero direction')
    raises(lambda: dvs.addLocalDV('z', body, count=2, direction='up'), "'normal' or a 3-vector", 'an unknown direction')
    raises(lambda: dvs.addLocalDV('z', body, points=[[np.nan, 0, 0]]), 'not finite', 'NaN control points')
    raises(lambda: dvs.addLocalDV('z', body, count=2, lower=np.nan, upper=1), 'both finite', 'NaN bounds')
    raises(lambda: dvs.addLocalDV('z', body, count=2, value=np.nan), 'not finite', 'a NaN start value')
    raises(lambda: dvs.setDesignVars({names[0]: np.nan}), 'not finite', 'a NaN value')
    raises(lambda: dvs.addLocalDV('z', body, count=2.5), 'whole number', 'a count that is not a whole number')
    raises(lambda: dvs.addLocalDV('z', body), 'give count= or points=', 'neither count nor points')
    raises(lambda: dvs.addLocalDV('z', body, points=[x0, x0 + 1e-9]), 'both hold', 'two control points on one point')
    raises(lambda: dvs.addLocalDV('z', body, points=[[0.3, 0, 2.5]]), 'farther than a tenth of the region', 'a given point far off the region')
    raises(lambda: dvs.addLocalDV('z', fixed, count=2), 'not on a region of role Fixed', 'a Fixed region')
    raises(lambda: dvs.addHandleDV('lift', body, translate=[0, 0, 1]), 'holds the control points', 'a body variable on a region of control points')
    raises(lambda: dvs.addLocalDV('bump', body, count=2), 'are defined already', 'names defined already')
    # a region without surface faces (the box's inner grid points): no normal, say so
    inner = sphere_in_box.box_region(ConstraintRegion, source, 'Handle', [-0.5, 0.5, -0.5, 0.5, 0.35, 0.5])  # noqa: F821
    deform.Regions = [body, fixed, floor, side, inner]
    raises(lambda: dvs.addLocalDV('cloud', inner, count=2), 'no surface normal', 'a region of points without surface faces')
    deform.Regions = [body, fixed, floor, side]
    check([(list(r.DesignVariables), list(r.ControlPoints)) for r in (body, side)] == rows and dvs.getVarNames() == names
          and dvs.getValues() == values, 'the failed calls changed nothing')
    check(np.array_equal(dvs.update(), X), 'and the deformation is the same bitwise')

    # a state file keeps the local variables and their control points
    restored = mlsdeform.DesignVariables(sphere_in_box.reloaded(os.path.join(work, 'state.pvsm'), plugin, globals()))
    check(restored.getVarNames() == names and restored.getValues() == values, 'a loaded state restores the local variables')
    check(np.array_equal(restored.update(), X), 'and deforms the same, bitwise')
    pvs.ResetSession()
    LoadPlugin(plugin, remote=False, ns=globals())

    # control lines through the thickness of an extruded slab: both points of a line move alike
    slab, sdvs, lines, top = slab_scene(os.path.join(work, 'slab.vtu'))
    srest = sphere_in_box.rest_points(slab)
    sdvs.setDesignVars({'top_1': 0.03})
    S = sdvs.update()
    held = sdvs.getControlPoints('top_1')['top_1']
    check(len(held[0]) == 2 and np.ptp(held[0][:, 0]) == 0 and np.ptp(held[0][:, 1]) == 0 and np.allclose(held[1], [0, 1, 0]),
          'a control line holds the 2 points through the thickness, its direction the face normal +y')
    lifted = [at(srest, x) for x in held[0]]
    check(np.abs(S[lifted] - srest[lifted] - [0, 0.03, 0]).max() <= 1e-9, 'the line moves by p (0, 1, 0)')
    front, back = srest[:, 2] < 0.05, srest[:, 2] > 0.05
    pairs = [at(srest[back], x + [0, 0, 0.1]) for x in srest[front]]
    d = S - srest
    check(np.abs(d[front] - d[back][pairs]).max() <= 1e-9, 'the slab stays extruded: front and back move alike (largest difference %.2g)'
          % np.abs(d[front] - d[back][pairs]).max())
    check(np.abs(S[:, 2] - srest[:, 2]).max() <= 1e-12, 'and stays in its planes (the Slip faces; round-off apart)')
    # a direction with a part along the line axis would move the lines along themselves (out of the
    # 2D case's planes, which the extruded deformation leaves out): refused, not dropped
    raises(lambda: slab_scene(os.path.join(work, 'slab-tilted.vtu'), direction=[0, 1, 1]), 'part along its line axis',
           'a direction along the control lines\' axis')
    # quadratic elements (a CalculiX deck's): the normals from their boundary faces, which VTK's
    # geometry filter gives float points; the faces must still meet the grid's own (double) points
    qslab, qdvs, qlines, qtop = slab_scene(os.path.join(work, 'slab-quadratic.vtu'), quadratic=True)
    qrest = sphere_in_box.rest_points(qslab)
    qdvs.setDesignVars({'top_1': 0.03})
    Q = qdvs.update()
    held = qdvs.getControlPoints('top_1')['top_1']
    lifted = [at(qrest, x) for x in held[0]]
    check(len(held[0]) == 3 and np.allclose(held[1], [0, 1, 0]) and np.abs(Q[lifted] - qrest[lifted] - [0, 0.03, 0]).max() <= 1e-9,
          'quadratic tetrahedra: a control line holds its 3 nodes through the thickness, moved by p along the face normal +y '
          '(%d nodes, direction %s)' % (len(held[0]), held[1]))
    np.savez(os.path.join(work, 'local.npz'), rest=rest, X=X, g=g, dJdp=np.array([dJdp[n] for n in names]),
             **{'dX_' + n: forward[n] for n in names})
else:
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    controller = vtkMultiProcessController.GetGlobalController()
    rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()  # noqa: F841
    reference = np.load(os.path.join(work, 'local.npz'))
    source = pvs.RedistributeDataSet(Input=pvs.OpenDataFile(os.path.join(work, 'scene.vtm')))
    deform, dvs, bumps, pair, _ = scene(source)
    dvs.setDesignVars({'bump_0': 0.02, 'bump_5': -0.03, 'pair_0': 0.04})
    X = dvs.update()
    rest = sphere_in_box.rest_points(deform)
    index = {tuple(x): i for i, x in enumerate(reference['rest'])}
    which = np.array([index.get(tuple(x), -1) for x in rest], dtype=int)
    check((which >= 0).all(), 'rank %d: each of its %d points is a point of the scene' % (rank, len(rest)))
    check(np.array_equal(X, reference['X'][which]), 'rank %d of %d: the points equal the serial ones bitwise' % (rank, ranks))
    dJdp = dvs.totalSensitivity(gradient(rest))
    mine = np.array([dJdp[n] for n in dvs.getVarNames()])
    check(np.array_equal(mine, reference['dJdp']), 'rank %d: dJ/dp of the 13 local variables equals the serial one bitwise' % rank)
    worst = max(np.abs(dvs.totalSensitivityProd({n: 1.0}) - reference['dX_' + n][which]).max() for n in dvs.getVarNames())
    check(worst == 0, 'rank %d: dX/dp at its points equals the serial one bitwise (largest difference %g)' % (rank, worst))

finish()
