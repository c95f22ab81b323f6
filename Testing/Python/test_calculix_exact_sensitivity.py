"""Issue 65: the exact structural shape gradient (mlsdeform.exactSensitivity, vtkCalculixSensitivity)
on the plate of Examples/Structural, checked against central differences of ccx's own responses,
in Debian's python3 with the plugin's folder on sys.path.

  python3 test_calculix_exact_sensitivity.py PLUGIN_FOLDER WORK
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

# ccx's responses in full precision (its sensitivity step's .sen0) for the central differences:
# the mass, the strain energy (half the point loads' work f . u: the compliance) and ALL-DISP
# over the tip nodes; each against the exact path's response of the same name
RESPONSES = (('MASS', 'MASS'), ('ENERGY', 'STRAINENERGY'), ('TIP', 'ALL-DISP, tip'))
EXACT = {'MASS': ('mass', None, 1.0), 'ENERGY': ('compliance', None, 0.5), 'TIP': ('all-disp', 'tip', 1.0)}

shutil.rmtree(work, ignore_errors=True)
deck = plate_design.make_source(os.path.join(work, 'source'), size=0.6, responses=RESPONSES)
# x1: the hole moved along the plate (the normal-only chain's wrong sign), r1: its radius, turn:
# both holes turned about their common centre
design = plate_design.PlateDesign(deck, work, variables=('x1', 'r1', 'turn'), responses=RESPONSES)
names = design.dvs.getVarNames()
base = dict.fromkeys(names, 0.0)
J, frd, quality = design.responses(base, 'base')
variant = frd[:-4] + '.inp'

# 1. The responses: the exact path's J is ccx's (the mass integrated as ccx integrates it, the
# compliance from the .frd's 6-digit displacements: 1e-5 allowed)
exact = {}
for name, (response, subset, factor) in EXACT.items():
    value, dJdX = mlsdeform.exactSensitivity(design.deform, variant, frd, response, set=subset)
    exact[name] = (value, dJdX)
    check(abs(factor * value - J[name]) <= 1e-5 * abs(J[name]), '%s: the exact path %.8g, ccx %.8g' % (name, factor * value, J[name]))
    check(np.isfinite(dJdX).all() and np.abs(dJdX).max() > 0, '%s: dJ/dX finite and not zero' % name)

# 2. Interior nodes carry the gradient too (ccx's own design set leaves them out): the mass's
# gradient over every node, dotted with X, is 3 M (the volume of the plate scaled by 1 + s grows
# as (1 + s)^3), exactly up to round-off
points = vtk_to_numpy(design.deform.GetOutput().GetPoints().GetData()).astype(float)
check(abs((exact['MASS'][1] * points).sum() / (3 * J['MASS']) - 1) < 1e-9,
      'sum of dM/dX . X is 3 M: %.12f' % ((exact['MASS'][1] * points).sum() / (3 * J['MASS'])))

# 3. dJ/dp by the exact path against central differences of ccx's responses, h and h / 2: both
# are derivatives of the same discrete J, so they agree to the differences' truncation error
# (O(h^2), seen as |d(h) - d(h/2)|) and the displacements' 6 digits (1e-5 of J): within 1% of the
# largest dJ/dp of the response, or the differences' own uncertainty where that is larger
chained = {name: design.dvs.totalSensitivity(exact[name][1]) for name in EXACT}
# beside it, ccx's own normal-only chain (readCalculixSensitivity), as the README's table shows it
_, normal_only, _ = design.evaluate(base, 'base')
steps = (2e-3, 1e-3)
rows = []
for variable in names:
    differences = {}
    for h in steps:
        plus, _, _ = design.responses(dict(base, **{variable: h}), 'plus')
        minus, _, _ = design.responses(dict(base, **{variable: -h}), 'minus')
        differences[h] = {r: (plus[r] - minus[r]) / (2 * h) for r in EXACT}
    for r, (_, _, factor) in EXACT.items():
        rows.append((variable, r, factor * chained[r][variable], differences[steps[0]][r], differences[steps[1]][r],
                     normal_only[r][variable]))
design.dvs.setDesignVars(base)
print('| variable | response | dJ/dp exact | central difference h = %g | h = %g | ccx\'s normal-only chain |' % steps)
print('|---|---|---|---|---|---|')
for row in rows:
    print('| %s | %s | %.6g | %.6g | %.6g | %.6g |' % row)
for variable, r, chain, d1, d2, _ in rows:
    largest = max(abs(row[4]) for row in rows if row[1] == r)
    uncertainty = abs(d1 - d2) + 1e-5 * J[r] / steps[1]
    check(abs(chain - d2) <= max(0.01 * largest, uncertainty),
          '%s, %s: exact %.6g against central differences %.6g (largest %.3g)' % (variable, r, chain, d2, largest))
    if abs(d2) > 0.05 * largest:
        check(np.sign(chain) == np.sign(d2), '%s, %s: the sign of the central difference' % (variable, r))

# 4. Bad input: an unknown response, a node set that does not exist, a result without U, an
# unsupported keyword named
raises(lambda: mlsdeform.exactSensitivity(design.deform, variant, frd, 'stress'), 'known: compliance', 'an unknown response')
raises(lambda: mlsdeform.exactSensitivity(design.deform, variant, frd, 'all-disp', set='nowhere'), 'no node set nowhere',
       'a node set that does not exist')
raises(lambda: mlsdeform.exactSensitivity(design.deform, variant, frd, 'all-disp', set='tip', adjoint_frd=frd),
       'is not the adjoint of this response', 'the primal result given as the adjoint one')
unsupported = os.path.join(work, 'base', 'nlgeom.inp')
with open(variant) as f:
    text = f.read()
with open(unsupported, 'w') as f:
    f.write(text.replace('*STEP\n*STATIC', '*STEP, NLGEOM\n*STATIC', 1))
raises(lambda: mlsdeform.exactSensitivity(design.deform, unsupported, frd, 'compliance'), 'NLGEOM', 'NLGEOM is refused by name')
with open(unsupported, 'w') as f:
    f.write(text.replace('*STATIC\n', '*STATIC\n*DLOAD\npart, BX, 2.\n', 1))
raises(lambda: mlsdeform.exactSensitivity(design.deform, unsupported, frd, 'compliance'), 'BX loads are not supported',
       'a body force other than gravity is refused by name')
with open(unsupported, 'w') as f:  # shells: the deck's first *STEP with a shell element and its section before it
    f.write(text.replace('*STEP\n', '*ELEMENT, TYPE=S3, ELSET=skin\n999999, 1, 2, 3\n*SHELL SECTION, ELSET=skin, MATERIAL=STEEL\n0.1\n*STEP\n', 1))
raises(lambda: mlsdeform.exactSensitivity(design.deform, unsupported, frd, 'compliance'), '*SHELL SECTION', 'shells are refused by name')
finish()
