"""Issue 66 points 2 and 7: constraint functions with exact gradients (mlsdeform.DesignConstraints),
in pvpython and split over MPI ranks.

  pvpython test_design_constraints.py PLUGIN WORK serial
      the sphere in a box with 13 local variables (sphere_in_box.local_scene): thicknesses across
      the sphere (1D and 2D toothpicks), its enclosed volume and area, a linear relation, the box's
      KS non-orthogonality and skewness; an extruded slab's volume by the 2D form; every value
      against its geometry, every gradient against central differences with h and h/2; the scipy
      list; bad input raises ValueError and adds nothing; writes WORK/constraints.npz;
  mpiexec -n N pvbatch --symmetric test_design_constraints.py PLUGIN WORK ranks
      every rank gets the same values and gradients, those of the serial run (summed in another
      order: to 1e-12 relative).
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
import mlsdeform  # noqa: E402

DESIGN = {'bump_0': 0.02, 'bump_3': -0.03, 'bump_7': 0.025, 'pair_0': 0.04}


def constraints(dvs):
    """The sphere's constraints; the design values are set after they are added (baseline p = 0)."""
    cons = mlsdeform.DesignConstraints(dvs)
    cons.addThicknessConstraints1D('thick1d', [[-0.2, 0, 0], [0.2, 0, 0]], 3, [0, 0, 1], surface='sphere', lower=0.9)
    cons.addThicknessConstraints2D('thick2d', [[-0.1, -0.15, 0.05], [-0.1, 0.15, 0.05]], [[0.15, -0.15, 0.05], [0.15, 0.15, 0.05]],
                                   2, 3, surface='sphere', lower=0.9, upper=1.1)
    cons.addTriangulatedVolumeConstraint('volume', surface='sphere', lower=1.0)
    cons.addSurfaceAreaConstraint('area', surface='sphere', scaled=False, upper=10.0)
    cons.addLinearConstraintsShape('linear', ['bump_0', 'bump_1'], ['bump_2', 'bump_3'], 1.0, [-1.0, 2.0], lower=-0.1, upper=0.1)
    cons.addMeshQualityConstraint('nonOrtho', 'nonOrthogonality', upper=70, rho=1.0)
    cons.addMeshQualityConstraint('skew', 'skewness', upper=4)
    cons.addMeshVolumeConstraint('cellVolume', cells='inner', lower=0.9)
    cons.addMeshVolumeConstraint('cellMass', cells='inner', density=2.5, scaled=False)
    return cons


def check_single_gradient(dvs, cons, name, what):
    """A one-value constraint's exact gradient against central differences with h = 1e-4 and h/2
    (as for the sphere's: FD(h) within 1e-4 of the largest entry, their extrapolation within 1e-7)."""
    start, names = dvs.getValues(), dvs.getVarNames()
    sens = {}
    cons.evalFunctionsSens(sens)
    J = np.array([sens[name][v] for v in names]).reshape(-1)
    fd = {}
    for h in (1e-4, 5e-5):
        fd[h] = np.zeros(len(names))
        for j, v in enumerate(names):
            for sign in (1, -1):
                dvs.setDesignVars({v: start[v] + sign * h})
                g = {}
                cons.evalFunctions(g)
                fd[h][j] += sign * g[name][0] / (2 * h)
            dvs.setDesignVars({v: start[v]})
    scale = np.abs(J).max()
    coarse, extrapolated = np.abs(fd[1e-4] - J).max() / scale, np.abs((4 * fd[5e-5] - fd[1e-4]) / 3 - J).max() / scale
    check(scale > 0 and coarse <= 1e-4 and extrapolated <= 1e-7,
          '%s: the exact gradient (largest %.3g) against central differences: %.2g (h = 1e-4), %.2g (extrapolated)'
          % (what, scale, coarse, extrapolated))


def flat(funcs):
    return np.concatenate([np.atleast_1d(funcs[n]) for n in sorted(funcs)])


def evaluate(cons):
    funcs, sens = {}, {}
    cons.evalFunctions(funcs)
    cons.evalFunctionsSens(sens)
    names = cons.dvs.getVarNames()
    jacobian = {n: np.array([sens[n][v] for v in names]).T for n in sens}
    return funcs, jacobian


if mode == 'serial':
    os.makedirs(work, exist_ok=True)
    path = os.path.join(work, 'scene.vtm')
    sphere_in_box.write_scene(path, 8, jitter=0.15)
    source = pvs.OpenDataFile(path)
    deform, dvs, bumps, pair, regions = sphere_in_box.local_scene(globals(), source)
    cons = constraints(dvs)
    check(cons.getConstraintNames() == ['thick1d', 'thick2d', 'volume', 'area', 'linear', 'nonOrtho', 'skew', 'cellVolume', 'cellMass'],
          'nine constraints added')
    base = {}
    cons.evalFunctions(base)
    # at the baseline the scaled values are 1; the absolute ones are the sphere's (a polyhedron of
    # 24 x 16 facets inscribed in r = 0.3: a little less than the sphere's)
    check(all(np.allclose(base[n], 1.0, rtol=0, atol=1e-14) for n in ('thick1d', 'thick2d', 'volume')), 'scaled values are 1 at the baseline')
    t1 = cons._constraints['thick1d'].baseline
    check(len(t1) == 3 and 0.58 < t1[1] <= 0.6 and t1[0] < t1[1] and abs(t1[0] - t1[2]) < 1e-12,
          'thickness along z at x = -0.2, 0, 0.2: %s (the chord 2 sqrt(0.09 - x^2) of the polyhedron)' % np.round(t1, 4))
    check(abs(t1[0] - 2 * np.sqrt(0.09 - 0.04)) < 0.02, 'at x = 0.2: %.4f, the sphere chord %.4f' % (t1[0], 2 * np.sqrt(0.05)))
    V0 = cons._constraints['volume'].baseline[0]
    check(0.95 * 4 / 3 * np.pi * 0.027 < V0 < 4 / 3 * np.pi * 0.027, 'the enclosed volume %.5f, under the sphere\'s %.5f' % (V0, 4 / 3 * np.pi * 0.027))
    check(0.97 * 4 * np.pi * 0.09 < base['area'][0] < 4 * np.pi * 0.09, 'the area %.5f, under the sphere\'s %.5f' % (base['area'][0], 4 * np.pi * 0.09))
    check(np.allclose(base['linear'], 0), 'the linear constraints are 0 at p = 0')
    ko, ks = base['nonOrtho'][0], base['skew'][0]
    check(cons.getBiasBound('nonOrtho') == np.log(cons._constraints['nonOrtho'].count) / 1.0, 'the bias bound is ln(N) / rho')
    field = deform.GetClientSideObject().GetOutputDataObject(0).GetFieldData()
    largest = field.GetArray('MaxNonOrthogonality').GetValue(0)
    check(largest <= ko <= largest + cons.getBiasBound('nonOrtho'),
          'KS non-orthogonality %.3f between the verdict\'s largest %.3f and it plus ln(N)/rho' % (ko, largest))
    largest = field.GetArray('MaxSkewness').GetValue(0)
    check(largest <= ks <= largest + cons.getBiasBound('skew'), 'KS skewness %.4f between the largest %.4f and the bound' % (ks, largest))

    # the cell set's volume: its tetrahedra's det / 6, the mass 2.5 times it
    def inner_volume():
        """The cell set's tetrahedra's |det| / 6 on the deformed points (doubles), the box after the sphere."""
        from vtkmodules.util.numpy_support import vtk_to_numpy
        X = dvs.update()
        out = deform.GetClientSideObject().GetOutputDataObject(0)
        blocks = [out.GetBlock(b) for b in range(out.GetNumberOfBlocks())]
        grid = blocks[1]
        P = X[blocks[0].GetNumberOfPoints():]
        tets = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
        tets = tets[vtk_to_numpy(grid.GetCellData().GetArray('inner')) == 1]
        a, b, c, d = (P[tets[:, k]] for k in range(4))
        return np.abs(np.einsum('ij,ij->i', np.cross(b - a, c - a), d - a)).sum() / 6
    V_inner = inner_volume()
    check(abs(cons._constraints['cellVolume'].baseline[0] - V_inner) <= 1e-14 and abs(base['cellMass'][0] - 2.5 * V_inner) <= 1e-14,
          "the cell set's volume %.12f = its tetrahedra's %.12f; its mass 2.5 x that" % (cons._constraints['cellVolume'].baseline[0], V_inner))
    raises(lambda: cons.addMeshVolumeConstraint('nocells', cells='outer'), "no volume mesh has the cell array 'outer'", 'an unknown cell set')
    raises(lambda: cons.addMeshVolumeConstraint('rho', cells='inner', density=-1), 'positive finite', 'a negative density')

    dvs.setDesignVars(DESIGN)
    funcs, jacobian = evaluate(cons)
    check(abs(funcs['cellVolume'][0] * cons._constraints['cellVolume'].baseline[0] - inner_volume()) <= 1e-13,
          'deformed: the cell set\'s volume is its tetrahedra\'s (%.12f)' % inner_volume())
    check(funcs['volume'][0] != 1.0 and funcs['thick1d'][1] != 1.0, 'the design changes the volume (%.5f) and the thicknesses (%s)'
          % (funcs['volume'][0], np.round(funcs['thick1d'], 5)))
    names = dvs.getVarNames()
    check(np.allclose(jacobian['linear'][:, :4], [[1, 0, -1, 0], [0, 1, 0, 2]]) and funcs['linear'][1] == 2 * -0.03,
          'the linear constraints: their values and constant rows')
    nonlinear, nonlinear_sens = {}, {}
    cons.evalFunctions(nonlinear, includeLinear=False)
    cons.evalFunctionsSens(nonlinear_sens, includeLinear=False)
    check(set(nonlinear) == set(nonlinear_sens) == set(funcs) - {'linear'}, 'includeLinear=False leaves the linear relations out (pyGeo\'s form)')
    # central differences of every value along every variable with h and h/2: the functions are
    # smooth in X (X linear in p), so FD(h) = exact + c h^2 + O(h^4) + eps |f| / h; the
    # extrapolation (4 FD(h/2) - FD(h)) / 3 removes the h^2 term (the mesh measures' is large:
    # acos' slope near 0 degrees) and must agree with the exact gradient to 1e-7 of its largest
    # entry (h^4 terms and round-off, 1e-9 here), and FD(h) itself to 1e-4
    start = dvs.getValues()
    fd = {}
    for h in (1e-4, 5e-5):
        fd[h] = {n: np.zeros_like(jacobian[n]) for n in jacobian}
        for j, v in enumerate(names):
            for sign in (1, -1):
                dvs.setDesignVars({v: start[v] + sign * h})
                f = {}
                cons.evalFunctions(f)
                for n in f:
                    fd[h][n][:, j] += sign * np.atleast_1d(f[n]) / (2 * h)
            dvs.setDesignVars({v: start[v]})
    for n in jacobian:
        scale = np.abs(jacobian[n]).max()
        coarse = np.abs(fd[1e-4][n] - jacobian[n]).max() / scale
        extrapolated = np.abs((4 * fd[5e-5][n] - fd[1e-4][n]) / 3 - jacobian[n]).max() / scale
        check(scale > 0 and coarse <= 1e-4 and extrapolated <= 1e-7,
              '%s: the exact gradient (largest %.3g) against central differences: %.2g (h = 1e-4), %.2g (h and h/2 extrapolated)'
              % (n, scale, coarse, extrapolated))
    check(dvs.getValues() == start, 'the design is back where it was')
    # the batched reverse mode: dense and (rows, values) gradients give totalSensitivity's dJ/dp
    rest = sphere_in_box.rest_points(deform)
    g = np.where(np.abs(rest[:, :1]) < 0.5, np.stack([np.sin(3 * rest[:, 0]), rest[:, 1], rest[:, 2] + 0.5], axis=1), 0.0)
    rows = np.flatnonzero(np.any(g != 0, axis=1))
    single = dvs.totalSensitivity(g)
    batch = dvs.totalSensitivities([g, (rows, g[rows]), (rows[:5], g[rows[:5]])])
    scale = max(abs(v) for v in single.values())
    check(all(abs(batch[k][n] - single[n]) <= 1e-14 * scale for k in (0, 1) for n in names) and
          abs(batch[2]['bump_0'] - dvs.totalSensitivity(np.where(np.isin(np.arange(len(g)), rows[:5])[:, None], g, 0.0))['bump_0']) <= 1e-14 * scale,
          'totalSensitivities: three functions at once (dense, as rows, a part) give totalSensitivity\'s dJ/dp')
    raises(lambda: dvs.totalSensitivities([(np.array([len(g)]), np.zeros((1, 3)))]), 'point indices', 'a row beyond the points')
    # the filter's surface measures refuse a polygon beyond the output's points, the value untouched
    from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIdTypeArray
    beyond, value = vtkIdTypeArray(), vtkDoubleArray()
    beyond.SetNumberOfComponents(3)
    beyond.InsertNextTuple3(0, 1, len(g))
    check(not dvs._algorithm.ComputeSurfaceArea(beyond, value, None, None) and value.GetNumberOfTuples() == 0 and
          'not one of the output' in dvs._algorithm.GetSensitivityError(),
          'ComputeSurfaceArea: a polygon beyond the points fails: %s' % dvs._algorithm.GetSensitivityError())

    # scipy's list: fun and jac of each side at x
    x = np.array([start[n] for n in names])
    scipy_cons = cons.getScipyConstraints()
    sides = sum((lo is not None) + (up is not None) for lo, up in cons.getBounds().values())
    check(len(scipy_cons) == sides == 16 and all(c['type'] == 'ineq' for c in scipy_cons),
          'scipy constraints: one inequality per finite bound (%d)' % len(scipy_cons))
    first = scipy_cons[0]
    check(np.allclose(first['fun'](x), funcs['thick1d'] - 0.9) and np.allclose(first['jac'](x), jacobian['thick1d']),
          'the first (thick1d >= 0.9): fun = value - lower, jac = its gradient')
    upper = [c for c in scipy_cons if np.allclose(c['fun'](x), 10.0 - funcs['area'])]
    check(len(upper) == 1 and np.allclose(upper[0]['jac'](x), -jacobian['area']), 'the area\'s upper bound: 10 - value, -gradient')

    # two bumps whose directions are far from parallel (for the leading-edge form's refusal below)
    held = dvs.getControlPoints()
    bump_names = [n for n in names if n.startswith('bump_')]
    skew_pair = next((a, b) for a in bump_names for b in bump_names
                     if abs(np.dot(held[a][1][0], held[b][1][0])) < 0.5 * np.linalg.norm(held[a][1][0]) * np.linalg.norm(held[b][1][0]))
    # bad input: a ValueError and no constraint added
    before = cons.getConstraintNames()
    raises(lambda: cons.addThicknessConstraints1D('out', [[0.5, 0.5, 0], [0.6, 0.5, 0]], 2, [0, 0, 1], surface='sphere'),
           'misses the surface', 'a thickness line that misses the surface')
    raises(lambda: cons.addThicknessConstraints1D('once', [[0, 0, 0.5], [0.01, 0, 0.5]], 2, [0, 0, 1], surface='sphere'),
           'on one side only', 'a thickness line that hits the surface once')
    raises(lambda: cons.addThicknessConstraints1D('zero', [[0, 0, 0], [0.1, 0, 0]], 2, [0, 0, 0]), 'not zero', 'a zero direction')
    raises(lambda: cons.addThicknessConstraints1D('nan', [[np.nan, 0, 0], [0.1, 0, 0]], 2, [0, 0, 1]), 'not finite', 'NaN points')
    raises(lambda: cons.addSurfaceAreaConstraint('nanb', surface='sphere', lower=np.nan), 'finite', 'a NaN bound')
    raises(lambda: cons.addSurfaceAreaConstraint('crossed', surface='sphere', lower=2, upper=1), 'exceeds', 'lower above upper')
    raises(lambda: cons.addSurfaceAreaConstraint('nowhere', surface='wing'), 'names no block with surface polygons', 'a surface name of no block')
    raises(lambda: cons.addSurfaceAreaConstraint('grid', surface='box'), 'names no block with surface polygons', 'a volume block as a surface')
    raises(lambda: cons.addLinearConstraintsShape('self', ['bump_0'], ['bump_0'], 1, 1), 'paired with itself', 'a variable paired with itself')
    raises(lambda: cons.addLinearConstraintsShape('none', ['bump_0'], ['bump_1'], 0, 0), 'no design variable influences', 'zero factors')
    raises(lambda: cons.addLinearConstraintsShape('unknown', ['wing_0'], ['bump_1'], 1, 1), 'unknown design variable', 'an unknown variable')
    raises(lambda: cons.addMeshQualityConstraint('q', 'aspectRatio'), 'measure is one of', 'an unknown measure')
    raises(lambda: cons.addMeshQualityConstraint('q', 'scaledJacobian'), 'no volume mesh gets an FEM solver', 'the scaled Jacobian of a CFD mesh')
    raises(lambda: cons.addMeshQualityConstraint('q', rho=-1), 'positive', 'a negative rho')
    raises(lambda: cons.addSurfaceAreaConstraint('volume', surface='sphere'), 'defined already', 'a name taken')
    check(cons.getConstraintNames() == before, 'the failed calls added nothing')
    deform.MeshQuality = 0
    raises(lambda: cons.addMeshQualityConstraint('off', 'skewness'), 'MeshQuality on', 'the mesh quality with MeshQuality off')
    deform.MeshQuality = 1

    # an extruded slab (a 2D case, ExtrusionAxis Z) whose surface is its side faces only (open at
    # the front and back): the 2D form's volume is the section's area times the depth; the 3D form
    # says the surface is open
    from vtkmodules.vtkCommonDataModel import vtkImageData, vtkMultiBlockDataSet, vtkPolyData, vtkCellArray
    from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
    from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
    from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataWriter
    image = vtkImageData()
    image.SetDimensions(11, 6, 2)
    image.SetSpacing(0.1, 0.1, 0.1)
    tets = vtkDataSetTriangleFilter()
    tets.SetInputData(image)
    tets.Update()
    surface = vtkGeometryFilter()
    surface.SetInputData(tets.GetOutput())
    surface.Update()
    whole = surface.GetOutput()
    sides = vtkPolyData()
    sides.SetPoints(whole.GetPoints())
    polys = vtkCellArray()
    for c in range(whole.GetNumberOfCells()):
        ids = whole.GetCell(c).GetPointIds()
        z = [whole.GetPoint(ids.GetId(k))[2] for k in range(ids.GetNumberOfIds())]
        if max(z) - min(z) > 1e-9:   # not on the front or back
            polys.InsertNextCell(ids)
    sides.SetPolys(polys)
    floor = vtkPolyData()   # the faces on the Fixed floor y = 0: points no variable moves
    floor.SetPoints(whole.GetPoints())
    polys = vtkCellArray()
    for c in range(whole.GetNumberOfCells()):
        ids = whole.GetCell(c).GetPointIds()
        if all(abs(whole.GetPoint(ids.GetId(k))[1]) < 1e-9 for k in range(ids.GetNumberOfIds())):
            polys.InsertNextCell(ids)
    floor.SetPolys(polys)
    from vtkmodules.vtkCommonCore import vtkStringArray
    verdict = vtkStringArray()
    verdict.SetName('QualityVerdict')
    verdict.InsertNextValue('FemSolver')   # as the Mesh File reader marks a structural deck: the FEM verdict
    tets.GetOutput().GetFieldData().AddArray(verdict)
    slab = vtkMultiBlockDataSet()
    slab.SetBlock(0, tets.GetOutput())
    slab.SetBlock(1, sides)
    slab.SetBlock(2, floor)
    for block, name in enumerate(('slab', 'sides', 'floor')):
        slab.GetMetaData(block).Set(vtkMultiBlockDataSet.NAME(), name)
    writer = vtkXMLMultiBlockDataWriter()
    writer.SetFileName(os.path.join(work, 'slab.vtm'))
    writer.SetInputData(slab)
    writer.Write()
    pvs.ResetSession()
    LoadPlugin(plugin, remote=False, ns=globals())
    source = pvs.OpenDataFile(os.path.join(work, 'slab.vtm'))
    box = lambda role, bounds: sphere_in_box.box_region(ConstraintRegion, source, role, bounds)  # noqa: E731,F821
    top = box('Handle', [-0.01, 1.01, 0.49, 0.51, -0.01, 0.11])
    regions = [top, box('Fixed', [-0.01, 1.01, -0.01, 0.01, -0.01, 0.11]), box('Slip', [-0.01, 1.01, -0.01, 0.51, -0.01, 0.01]),
               box('Slip', [-0.01, 1.01, -0.01, 0.51, 0.09, 0.11])]
    slabDeform = MLSDeform(Input=source, Regions=regions, NumberOfSamples=60, ExtrusionAxis='Z')  # noqa: F821
    sdvs = mlsdeform.DesignVariables(slabDeform)
    sdvs.addLocalDV('top', top, count=4, axis=[0, 0, 1], lower=-0.05, upper=0.05)
    scons = mlsdeform.DesignConstraints(sdvs)
    raises(lambda: scons.addTriangulatedVolumeConstraint('v3', surface='sides'), 'not closed', 'an open surface for an enclosed volume')
    scons.addTriangulatedVolumeConstraint('v2', surface='sides', axis=[0, 0, 1], scaled=False)
    scons.addThicknessConstraints2D('t', [[0.05, 0.25, 0.0], [0.05, 0.25, 0.1]], [[0.95, 0.25, 0.0], [0.95, 0.25, 0.1]], 1, 4,
                                    surface='sides', scaled=False)
    f = {}
    scons.evalFunctions(f)
    srest = sphere_in_box.rest_points(slabDeform)
    depth = np.ptp(srest[:, 2])   # 0.1 as a float32 (the image's points)
    check(abs(f['v2'][0] - 0.5 * depth) < 1e-15 and np.allclose(f['t'], 0.5, atol=1e-12),
          'the slab: volume %.15f = 1 x 0.5 x its depth, thicknesses %s = 0.5 (lines at mid-depth along y)' % (f['v2'][0], f['t']))
    sdvs.setDesignVars({'top_1': 0.03, 'top_2': -0.02})
    S = sdvs.update()
    f = {}
    scons.evalFunctions(f)
    front = (np.abs(srest[:, 1] - 0.5) < 1e-9) & (np.abs(S[:, 2]) < 1e-9)
    order = np.argsort(S[front, 0])
    xs, ys = S[front][order, 0], S[front][order, 1]
    section = np.trapz(ys, xs)   # the top is a polyline over the floor y = 0: the section's area
    check(abs(f['v2'][0] - depth * section) < 1e-15, 'deformed: the 2D volume %.15f = the section\'s area x depth %.15f'
          % (f['v2'][0], depth * section))
    check_single_gradient(sdvs, scons, 'v2', 'the 2D form of the enclosed volume')
    raises(lambda: scons.addSurfaceAreaConstraint('held', surface='floor'), 'no design variable influences',
           'a constraint on points no variable moves (the Fixed floor)')
    # the leading/trailing-edge form on two control lines of one direction (+y): p_0 + p_3 = 0, an
    # equality (scipy 'eq'); directions that are not parallel cannot hold a midpoint
    scons.addLeTeConstraints('edge', 'top_0', 'top_3')
    f, sens = {}, {}
    scons.evalFunctions(f)
    scons.evalFunctionsSens(sens)
    snames = sdvs.getVarNames()
    values = sdvs.getValues()
    check(np.allclose(f['edge'], values['top_0'] + values['top_3'], atol=1e-15) and
          [sens['edge'][n][0] for n in snames] == [1.0 if n in ('top_0', 'top_3') else 0.0 for n in snames],
          'addLeTeConstraints: p_0 + p_3 = %s, its row %s' % (f['edge'], [sens['edge'][n][0] for n in snames]))
    equalities = [c for c in scons.getScipyConstraints() if c['type'] == 'eq']
    check(len(equalities) == 1 and np.allclose(equalities[0]['fun'](np.array([values[n] for n in snames])), f['edge']),
          'and the scipy list holds it as the one equality')
    raises(lambda: cons.addLeTeConstraints('tilted', *skew_pair), 'not parallel', 'leading-edge variables of directions not parallel')
    # trust-constr tries points beyond the variables' bounds: the scipy list evaluates there as at
    # the bound (clipped), and the run ends within the bounds and the constraint
    from scipy.optimize import Bounds, minimize
    tcons = mlsdeform.DesignConstraints(sdvs)
    tcons.addTriangulatedVolumeConstraint('area2d', surface='sides', axis=[0, 0, 1], lower=0.99, upper=1.01)
    sdvs.setDesignVars(dict.fromkeys(snames, 0.0))
    beyond = np.array([0.08] + [0.0] * (len(snames) - 1))   # top_0 beyond its upper bound 0.05
    at_beyond = tcons.getScipyConstraints()[0]['fun'](beyond)
    sdvs.setDesignVars(dict(zip(snames, np.clip(beyond, -0.05, 0.05))))
    f = {}
    tcons.evalFunctions(f)
    check(np.allclose(at_beyond, f['area2d'] - 0.99) and sdvs.getValues()['top_0'] == 0.05,
          'the scipy list evaluates beyond a bound (top_0 = 0.08) as at the bound: %s' % at_beyond)
    target = np.array([0.04, 0.04, -0.04, 0.04])
    result = minimize(lambda x: float((np.clip(x, -0.05, 0.05) - target) @ (np.clip(x, -0.05, 0.05) - target)), np.zeros(len(snames)),
                      jac=lambda x: 2 * (np.clip(x, -0.05, 0.05) - target),
                      method='trust-constr', bounds=Bounds([-0.05] * len(snames), [0.05] * len(snames)),
                      constraints=tcons.getScipyConstraints(), options={'maxiter': 60})
    tcons._set(result.x)
    f = {}
    tcons.evalFunctions(f)
    check(np.all(np.abs(result.x) <= 0.05 + 1e-8) and 0.99 - 1e-6 <= f['area2d'][0] <= 1.01 + 1e-6,
          'trust-constr runs through: x %s within the bounds, the area %.5f within [0.99, 1.01] (%s)'
          % (np.round(result.x, 4), f['area2d'][0], result.message))
    # the FEM verdict's least scaled Jacobian as a smooth lower bound, and its gradient
    scons.addMeshQualityConstraint('sj', 'scaledJacobian', lower=0.2, rho=30.0)
    raises(lambda: scons.addMeshQualityConstraint('no', 'skewness'), "no volume mesh has checkMesh's face measures",
           'a CFD measure on an FEM mesh')
    f = {}
    scons.evalFunctions(f)
    least = slabDeform.GetClientSideObject().GetOutputDataObject(0).GetFieldData().GetArray('MinScaledJacobian').GetValue(0)
    check(least - scons.getBiasBound('sj') <= f['sj'][0] <= least,
          'KS scaled Jacobian %.4f between the verdict\'s least %.4f less ln(N)/rho and the least' % (f['sj'][0], least))
    check_single_gradient(sdvs, scons, 'sj', 'scaled Jacobian')

    # the volume of the slab's cells as its solver measures it: quadratic tetrahedra of an FEM mesh
    # (C3D10, as CalculiX integrates them) and voxels of a CFD mesh (OpenFOAM's face pyramids);
    # 1 x 0.5 x the depth at rest, the gradient against central differences
    from vtkmodules.vtkFiltersCore import vtkAppendFilter
    from vtkmodules.vtkFiltersGeometry import vtkLinearToQuadraticCellsFilter
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
    quadratic = vtkLinearToQuadraticCellsFilter()
    quadratic.SetInputData(tets.GetOutput())   # its field data QualityVerdict FemSolver: the FEM verdict
    quadratic.SetOutputPointsPrecision(1)
    voxels = vtkAppendFilter()
    voxels.SetInputData(image)
    for kind, cells in (('C3D10', quadratic), ('voxels', voxels)):
        writer = vtkXMLUnstructuredGridWriter()
        writer.SetFileName(os.path.join(work, 'slab-%s.vtu' % kind))
        writer.SetInputConnection(cells.GetOutputPort())
        writer.Write()
        source = pvs.OpenDataFile(os.path.join(work, 'slab-%s.vtu' % kind))
        box = lambda role, bounds: sphere_in_box.box_region(ConstraintRegion, source, role, bounds)  # noqa: E731,F821
        top = box('Handle', [-0.01, 1.01, 0.49, 0.51, -0.01, 0.11])
        vdeform = MLSDeform(Input=source, Regions=[top, box('Fixed', [-0.01, 1.01, -0.01, 0.01, -0.01, 0.11])],  # noqa: F821
                            NumberOfSamples=60, ExtrusionAxis='Z')
        vdvs = mlsdeform.DesignVariables(vdeform)
        vdvs.addLocalDV('top', top, count=4, axis=[0, 0, 1], lower=-0.05, upper=0.05)
        vcons = mlsdeform.DesignConstraints(vdvs)
        vcons.addMeshVolumeConstraint('V', scaled=False)
        f = {}
        vcons.evalFunctions(f)
        depth = np.ptp(sphere_in_box.rest_points(vdeform)[:, 2])
        check(abs(f['V'][0] - 0.5 * depth) <= 1e-15, '%s: the volume %.15f = 1 x 0.5 x the depth' % (kind, f['V'][0]))
        vdvs.setDesignVars({'top_1': 0.03, 'top_2': -0.02})
        check_single_gradient(vdvs, vcons, 'V', '%s volume' % kind)
    # a surface's polygons leave out another process's held as ghosts (counted there): two
    # triangles after a vertex, the second a ghost
    from vtkmodules.vtkCommonCore import vtkPoints, vtkUnsignedCharArray
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkDataSetAttributes, vtkPolyData
    ghosted = vtkPolyData()
    corners = vtkPoints()
    for x in ((0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)):
        corners.InsertNextPoint(x)
    ghosted.SetPoints(corners)
    verts, polys = vtkCellArray(), vtkCellArray()
    verts.InsertNextCell(1, [0])
    polys.InsertNextCell(3, [0, 1, 2])
    polys.InsertNextCell(3, [1, 3, 2])
    ghosted.SetVerts(verts)
    ghosted.SetPolys(polys)
    flags = vtkUnsignedCharArray()
    flags.SetName(vtkDataSetAttributes.GhostArrayName())
    for value in (0, 0, vtkDataSetAttributes.DUPLICATECELL):  # the vertex, then the two triangles
        flags.InsertNextValue(value)
    ghosted.GetCellData().AddArray(flags)
    offsets, connectivity = mlsdeform.constraints._polygons(ghosted)
    check(list(offsets) == [0, 3] and list(connectivity) == [0, 1, 2], 'a ghost polygon is left out of a surface (%s)' % list(connectivity))
    np.savez(os.path.join(work, 'constraints.npz'), **{'f_' + n: np.atleast_1d(v) for n, v in funcs.items()},
             **{'J_' + n: v for n, v in jacobian.items()})
else:
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    controller = vtkMultiProcessController.GetGlobalController()
    rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    reference = np.load(os.path.join(work, 'constraints.npz'))
    source = pvs.RedistributeDataSet(Input=pvs.OpenDataFile(os.path.join(work, 'scene.vtm')))
    deform, dvs, bumps, pair, _ = sphere_in_box.local_scene(globals(), source)
    cons = constraints(dvs)
    dvs.setDesignVars(DESIGN)
    funcs, jacobian = evaluate(cons)
    # the mesh-quality aggregates too: the faces between the ranks' pieces measured across them
    for n in ('thick1d', 'thick2d', 'volume', 'area', 'linear', 'cellVolume', 'cellMass', 'nonOrtho', 'skew'):
        f, J = np.atleast_1d(funcs[n]), jacobian[n]
        check(np.allclose(f, reference['f_' + n], rtol=1e-12, atol=0) and
              np.abs(J - reference['J_' + n]).max() <= 1e-10 * np.abs(reference['J_' + n]).max(),
              'rank %d of %d: %s and its gradient are the serial ones (values to 1e-12, gradients to 1e-10)' % (rank, ranks, n))
    for n in ('nonOrtho', 'skew'):
        mine = np.concatenate([np.atleast_1d(funcs[n]), jacobian[n].reshape(-1)])
        everyone = mlsdeform.ranks.all_gather(mine).reshape(ranks, -1)
        check(np.array_equal(everyone[0], mine), 'rank %d: %s and its gradient are rank 0\'s, bitwise' % (rank, n))

finish()
