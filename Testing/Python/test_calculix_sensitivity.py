"""Issue 55, point 5: CalculiX's shape sensitivities chained to dJ/dp (mlsdeform.readCalculixSensitivity,
DesignVariables.totalSensitivity) on the plate of Examples/Structural (plate_design.py), in Debian's
python3 with the plugin's folder on sys.path.

  python3 test_calculix_sensitivity.py PLUGIN_FOLDER WORK
"""
import os
import shutil
import sys

import numpy as np

plugin, work = sys.argv[1:3]
sys.path.insert(0, plugin)
here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(here)), 'Examples', 'Structural'))
import mlsdeform  # noqa: E402
import plate_design  # noqa: E402
from checks import check, finish, raises  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

shutil.rmtree(work, ignore_errors=True)
deck = plate_design.make_source(os.path.join(work, 'source'), size=0.6)
design = plate_design.PlateDesign(deck, work, variables=('x1', 'y1', 'r1', 'r2', 'fillet'))
J, frd, quality = design.responses(dict.fromkeys(design.dvs.getVarNames(), 0.0), 'base')
points = lambda: vtk_to_numpy(design.deform.GetOutput().GetPoints().GetData()).astype(float)  # noqa: E731

# 1. dJ/dX read from the run: ccx's derivative along each surface node's normal. For the mass, the
# sum over the surface of g . x is d/ds of the mass of the part scaled by 1 + s: 3 M (the clamped face,
# which ccx leaves without normals, has x = 0). Bound: the averaged normals at edges and the corner
# nodes of the quadratic faces, a discretization error of the surface, 0.05% on this mesh; 1% allowed.
g = mlsdeform.readCalculixSensitivity(design.deform, frd, 'MASS')
x = points()
check(abs((g * x).sum() / (3 * J['MASS']) - 1) < 1e-2, 'sum of dM/dX . X over the surface is 3 M: %.5f' % ((g * x).sum() / (3 * J['MASS'])))
ids = vtk_to_numpy(design.deform.GetOutput().GetPointData().GetArray('NodeId'))
surface = set(int(n) for n in open(deck.replace('plate.inp', 'mesh.inp')).read().split('*NSET,NSET=surface\n', 1)[1].split('*', 1)[0]
              .replace(',', ' ').split())
check(all(int(n) in surface for n in ids[np.abs(g).sum(axis=1) > 0]), 'dJ/dX is zero off the surface design nodes')
check(abs(mlsdeform.readCalculixObjective(frd, 'mass') - J['MASS']) == 0 and J['TIP'] > 0,
      'the responses by name, any case, in full precision (.sen0): MASS %.6g, TIP %.6g' % (J['MASS'], J['TIP']))

# 2. The chain is exact: totalSensitivity(dJ/dX) is sum dJ/dX . dX/dp, dX/dp here by central
# differences of the deformation (delta 1e-5: the MLS map is smooth in p, its truncation error
# O(delta^2) ~ 1e-10 relative; the deformation's solve is exact to 1e-12).
chained = design.dvs.totalSensitivity(g)
values = dict.fromkeys(design.dvs.getVarNames(), 0.0)
for name in ('r1', 'fillet'):
    shifted = []
    for sign in (1, -1):
        design.dvs.setDesignVars(dict(values, **{name: sign * 1e-5}))
        design.dvs._updated()
        shifted.append(points())
    by_difference = float((g * (shifted[0] - shifted[1]) / 2e-5).sum())
    check(abs(chained[name] - by_difference) <= 1e-6 * abs(by_difference),
          'dM/d%s by the chain %.9g, by dX/dp differences %.9g' % (name, chained[name], by_difference))
design.dvs.setDesignVars(values)

# 3. Against central differences of ccx's responses (two more ccx runs a variable and step): the
# differences are stable in h (ccx's responses in full precision; truncation O(h^2): agreement to
# 1e-3 allowed), and the chain agrees with them up to the discretization gap: ccx's derivative
# sees the surface nodes' normal motion only, not the interior nodes' and the tangential motion a
# morph also makes (README). On the strong variables (the radii: the largest dJ/dp) that gap is
# 1-5% on meshes of 1.6k to 13k nodes and shrinks as O(h); 10% allowed on this coarse one. On every
# variable that changes J the sign agrees.
rows = plate_design.validate(design, steps=(2e-3, 1e-3))
print(plate_design.table(rows))
for name, response, chain, differences in rows:
    fd = differences[1e-3]
    # (the differences' round-off: J's own, about 1e-12 of it after ccx's sums over the elements,
    # over the step h = 1e-3: a response that does not change, such as the mass under a
    # translation, differs by that noise alone)
    check(abs(differences[2e-3] - fd) <= 1e-3 * abs(fd) + 1e-12 * J[response] / 1e-3,
          '%s, %s: the central difference is stable in h' % (name, response))
    largest = max(abs(r[3][1e-3]) for r in rows if r[1] == response)
    if abs(fd) > 1e-2 * largest:
        check(np.sign(chain) == np.sign(fd), '%s, %s: the chain %.4g has the central difference\'s sign (%.4g)' % (name, response, chain, fd))
    if name in ('r1', 'r2'):
        check(abs(chain - fd) <= 0.1 * abs(fd), '%s, %s: the chain %.5g within 10%% of the central difference %.5g' % (name, response, chain, fd))

# 4. Bad input: an unknown response, a run on another shape, a run without WRITE.
raises(lambda: mlsdeform.readCalculixSensitivity(design.deform, frd, 'STRESS'), 'MASS, TIP', 'an unknown response names the ones there are')
design.dvs.setDesignVars(dict(values, r1=0.1))
raises(lambda: mlsdeform.readCalculixSensitivity(design.deform, frd, 'MASS'), 'another shape', 'a run on another design is refused')
design.dvs.setDesignVars(values)
os.remove(frd[:-4] + '.sen1')
raises(lambda: mlsdeform.readCalculixSensitivity(design.deform, frd, 'MASS'), '*SENSITIVITY, WRITE', 'a run without WRITE says what it needs')
raises(lambda: mlsdeform.readCalculixSensitivity(design.deform, frd[:-4] + '.inp', 'MASS'), '.frd', 'a deck is not a result file')
finish()
