"""Issue 65, point 3: the exact shape gradient (vtkCalculixSensitivity) integrates every solid element
type as ccx does. For each of C3D4, C3D10, C3D8, C3D20, C3D20R, C3D6 and C3D15: a cantilever of
4 x 1 x 1 mm in 4 x 2 x 2 hexahedra (split into 2 wedges or 6 tetrahedra a hexahedron), its nodes
moved by a smooth field so that the elements are distorted and, where quadratic, curved; clamped at
x = 0 and pulled down at x = 4. dJ/dp of the compliance f . u along a design field V (every node,
interior and midside too) by the exact path against central differences of ccx's compliance on the
decks X +- h V (h and h / 2); u from *NODE FILE, DOUBLE (full precision: with the ASCII .frd's six
digits dJ/dX is good to about 1e-3 only). In Debian's python3 with the plugin's folder on sys.path.

  python3 test_calculix_elements.py PLUGIN_FOLDER WORK
"""
import itertools
import math
import os
import shutil
import subprocess
import sys

import numpy as np

plugin, work = sys.argv[1:3]
sys.path.insert(0, plugin)
from mlsdeform import calculix  # noqa: E402
from mlsdeform.deformer import _load_wrapping  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from checks import check, finish  # noqa: E402

L, W, T = 4.0, 1.0, 1.0
# the central differences' steps (of ccx's compliance in full precision): truncation O(h^2)
STEPS = (0.01, 0.005)
NX, NY, NZ = 4, 2, 2
CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
WEDGE_EDGES = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
# a hexahedron's corners split into two wedges (bottom, then top triangles) and six tetrahedra about
# the diagonal 0-6
WEDGES = [(0, 1, 2, 4, 5, 6), (0, 2, 3, 4, 6, 7)]
# ccx's faces (e_c3d.f's ifaceq, ifacet, ifacew; corners, 1-based in the deck's order), to find the
# elements' faces on the top z = T that the pressure loads
FACES = {'hex': [(4, 3, 2, 1), (5, 6, 7, 8), (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8)],
         'tet': [(1, 3, 2), (1, 2, 4), (2, 3, 4), (1, 4, 3)],
         'wedge': [(1, 3, 2), (4, 5, 6), (1, 2, 5, 4), (2, 3, 6, 5), (4, 6, 3, 1)]}
TETS = [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]


def position(g):
    """The node at grid point g of the doubled grid (spacing half a cell), distorted smoothly."""
    x, y, z = g[0] * L / (2 * NX), g[1] * W / (2 * NY), g[2] * T / (2 * NZ)
    return (x + 0.04 * math.sin(2.1 * y + 1.3 * z), y + 0.05 * math.sin(1.7 * x) * z, z + 0.04 * math.cos(1.1 * x + 0.7 * y))


def elements(kind):
    """[(grid points of each element's nodes, ccx's order)] of the element type."""
    out = []
    for i, j, k in itertools.product(range(NX), range(NY), range(NZ)):
        corner = [(2 * (i + a), 2 * (j + b), 2 * (k + c)) for a, b, c in CORNERS]
        mid = lambda p, q: tuple((p[d] + q[d]) // 2 for d in range(3))  # noqa: E731
        if kind in ('C3D8', 'C3D20', 'C3D20R'):
            nodes = corner + ([mid(corner[a], corner[b]) for a, b in HEX_EDGES] if kind != 'C3D8' else [])
            out.append(nodes)
        elif kind in ('C3D6', 'C3D15'):
            for w in WEDGES:
                c = [corner[n] for n in w]
                out.append(c + ([mid(c[a], c[b]) for a, b in WEDGE_EDGES] if kind == 'C3D15' else []))
        else:
            for t in TETS:
                c = [corner[n] for n in t]
                p = [np.array(position(g)) for g in c]
                if np.dot(p[1] - p[0], np.cross(p[2] - p[0], p[3] - p[0])) < 0:
                    c[1], c[2] = c[2], c[1]
                out.append(c + ([mid(c[a], c[b]) for a, b in TET_EDGES] if kind == 'C3D10' else []))
    return out


def write_deck(path, kind, field=None, h=0.0, load='tip'):
    """The cantilever's deck of element type kind, its nodes at X + h V (13 digits: ccx reads 20
    characters a field); load 'gravity' adds a body force as large as the tip load (its derivative:
    the elements' volumes move with the nodes), 'pressure' a pressure as large on the top faces
    (their areas and normals move)."""
    cells = elements(kind)
    grid = sorted({g for cell in cells for g in cell})
    number = {g: n + 1 for n, g in enumerate(grid)}
    X = np.array([position(g) for g in grid])
    if field is not None:
        X = X + h * field
    fixed = [number[g] for g in grid if g[0] == 0]
    loaded = [number[g] for g in grid if g[0] == 2 * NX]
    lines = ['*NODE, NSET=all'] + ['%d, %.13g, %.13g, %.13g' % (n + 1, *x) for n, x in enumerate(X)]
    lines.append('*ELEMENT, TYPE=%s, ELSET=part' % kind)
    lines.insert(0, '*DESIGNVARIABLES, TYPE=COORDINATE\nall')
    for e, cell in enumerate(cells):
        ids = [number[g] for g in cell]
        rows = [ids[s:s + 15] for s in range(0, len(ids), 15)]  # ccx continues an element's line after 15 nodes
        lines.append('%d, ' % (e + 1) + ',\n'.join(', '.join(map(str, r)) for r in rows))
    lines += ['*NSET, NSET=fixed'] + ['%d,' % n for n in fixed]
    lines += ['*MATERIAL, NAME=STEEL', '*ELASTIC', '210000., 0.3', '*DENSITY', '7.85e-9', '*SOLID SECTION, ELSET=part, MATERIAL=STEEL',
              '*STEP', '*STATIC', '*BOUNDARY', 'fixed, 1, 3', '*CLOAD'] + ['%d, 3, %.9g' % (n, -10.0 / len(loaded)) for n in loaded]
    if load == 'gravity':  # rho g V = 7.85e-9 * 3.2e8 * 4: about 10 N, as the tip load
        lines += ['*DLOAD', 'part, GRAV, 3.2e8, 0.3, 0., -1.']
    if load == 'pressure':  # 2.5 MPa on the top's 4 mm^2
        family = 'hex' if kind.startswith('C3D8') or kind.startswith('C3D20') else 'tet' if kind in ('C3D4', 'C3D10') else 'wedge'
        lines.append('*DLOAD')
        for e, cell in enumerate(cells):
            for f, corners in enumerate(FACES[family]):
                if all(cell[c - 1][2] == 2 * NZ for c in corners):
                    lines.append('%d, P%d, 2.5' % (e + 1, f + 1))
    lines += ['*NODE FILE, DOUBLE', 'U', '*END STEP']  # u in full precision
    # ccx's strain energy in full precision (JOB.sen0 of its sensitivity step): half the compliance
    lines += ['*STEP', '*SENSITIVITY, WRITE', '*DESIGNRESPONSE, NAME=ENERGY', 'STRAINENERGY', '*END STEP']
    with open(path, 'w') as f:
        f.write('\n'.join(lines) + '\n')
    return path, X


def ccx(deck):
    folder, name = os.path.split(deck)
    result = subprocess.run(['ccx', '-i', name[:-4]], cwd=folder, capture_output=True, text=True)
    if result.returncode != 0 or '*ERROR' in result.stdout + result.stderr:
        raise RuntimeError('ccx failed on %s:\n%s' % (deck, (result.stdout + result.stderr)[-1500:]))
    return deck[:-4] + '.frd'


def ccx_compliance(frd):
    """Twice ccx's strain energy of the run (its .sen0, full precision): the compliance f . u."""
    with open(frd[:-4] + '.sen0') as f:
        return 2 * float(f.read().split()[0].replace('D', 'E'))


def response(deck, frd, kind=0, gradient=False):
    """J (and dJ/dX) of the deck's run: the compliance (kind 0) or the KS-aggregated stress (5,
    reference 100 MPa, weight 10; its adjoint deck written and run by ccx for the gradient)."""
    s = _load_wrapping(readers=True).vtkCalculixSensitivity()
    s.SetDeckFileName(deck)
    s.SetResultFileName(frd)
    s.SetResponse(kind)
    s.SetKSWeight(10.0)
    s.SetReferenceStress(100.0)
    if gradient and s.NeedsAdjoint():
        adjoint = calculix.writeAdjointDeck(s, deck, deck[:-4] + '-adjoint.inp')
        s.SetAdjointResultFileName(ccx(adjoint))
    if not (s.Compute() if gradient else s.ComputeValue()):
        raise RuntimeError(s.GetLastError())
    return s.GetValue(), (vtk_to_numpy(s.GetGradient()).reshape(-1, 3) if gradient else None)


def compliance(deck, frd, gradient=False):
    return response(deck, frd, 0, gradient)


def check_derivative(name, stem, kind, load, J, dJdX, X, value):
    """dJ/dp along a design field V that moves every node (a smooth bulge and a random part; the
    clamped face too) by the exact gradient against central differences of value(deck, frd) on the
    decks X +- h V (h and h / 2): both are derivatives of the same discrete J (u and ccx's energies
    in full precision), so they agree to the differences' truncation error, O(h^2), seen as
    |d(h) - d(h/2)| (twice it allowed), or 1e-4 of dJ/dp (the issue asks for 1%)."""
    V = np.stack([0.2 * np.sin(math.pi * X[:, 0] / L), 0.1 * X[:, 2], 0.3 * X[:, 1] * X[:, 0] / L], axis=1)
    V += 0.02 * random.standard_normal(V.shape)
    exact = float((dJdX * V).sum())
    differences = []
    for h in STEPS:
        values = []
        for sign in (1, -1):
            shifted, _ = write_deck(os.path.join(work, '%s-%s.inp' % (stem, 'plus' if sign > 0 else 'minus')), kind, V, sign * h, load)
            values.append(value(shifted, ccx(shifted)))
        differences.append((values[0] - values[1]) / (2 * h))
    print('| %s | %.6g | %.6g | %.6g | %.2e |' % (name, exact, differences[0], differences[1], abs(exact - differences[1]) / abs(differences[1])))
    check(abs(exact - differences[1]) <= max(1e-4 * abs(differences[1]), 2 * abs(differences[0] - differences[1])),
          '%s: dJ/dp exact %.6g against ccx central differences %.6g (J = %.6g)' % (name, exact, differences[1], J))


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
random = np.random.default_rng(3)
KINDS = ('C3D4', 'C3D10', 'C3D8', 'C3D20', 'C3D20R', 'C3D6', 'C3D15')
print('| element | compliance: dJ/dp exact | central difference h = %g | h = %g | gap |' % STEPS)
print('|---|---|---|---|---|')
for kind, load in itertools.product(KINDS, ('tip', 'gravity', 'pressure')):
    name = kind + ('' if load == 'tip' else ' with ' + load)
    deck, X = write_deck(os.path.join(work, '%s-%s.inp' % (kind, load)), kind, load=load)
    frd = ccx(deck)
    J, dJdX = compliance(deck, frd, gradient=True)
    check(abs(J - ccx_compliance(frd)) <= 1e-8 * J, '%s: f . u from the .frd %.10g, twice ccx\'s strain energy %.10g' % (name, J, ccx_compliance(frd)))
    check_derivative(name, '%s-%s' % (kind, load), kind, load, J, dJdX, X, lambda deck, frd: ccx_compliance(frd))
# The KS-aggregated von Mises stress (tip load): its own adjoint run, against central differences of
# the aggregate of ccx's stresses (u in full precision)
print('| element | KS stress: dJ/dp exact | central difference h = %g | h = %g | gap |' % STEPS)
print('|---|---|---|---|---|')
for kind in KINDS:
    deck, X = write_deck(os.path.join(work, kind + '-stress.inp'), kind)
    J, dJdX = response(deck, ccx(deck), 5, gradient=True)
    check_derivative(kind, kind + '-stress', kind, 'tip', J, dJdX, X, lambda deck, frd: response(deck, frd, 5)[0])
# Bad input: a result of another mesh, of another shape, an element set that does not exist, a
# mass without densities (it does not depend on the design)
def error_of(call):
    try:
        call()
    except RuntimeError as e:
        print('expected error: %s' % e)
        return str(e)
    return ''


tet, X = write_deck(os.path.join(work, 'bad-tet.inp'), 'C3D4')
quadratic, _ = write_deck(os.path.join(work, 'bad-quadratic.inp'), 'C3D10')
moved, _ = write_deck(os.path.join(work, 'bad-moved.inp'), 'C3D4', np.ones(X.shape), 0.01)
tet_frd, quadratic_frd = ccx(tet), ccx(quadratic)
check('another mesh' in error_of(lambda: response(tet, quadratic_frd)), 'a result of another mesh is refused')
check('another shape' in error_of(lambda: response(moved, tet_frd)), 'a result of another shape is refused')
s = _load_wrapping(readers=True).vtkCalculixSensitivity()
s.SetDeckFileName(tet)
s.SetResponse(1)
s.SetResponseSet('nowhere')
check(not s.Compute() and 'no element set nowhere' in s.GetLastError(), 'an element set that does not exist is named')
with open(tet) as f:
    text = f.read()
with open(os.path.join(work, 'bad-density.inp'), 'w') as f:
    f.write(text.replace('*DENSITY\n7.85e-9\n', ''))
s.SetDeckFileName(os.path.join(work, 'bad-density.inp'))
s.SetResponseSet('')
check(not s.Compute() and 'no *DENSITY' in s.GetLastError(), 'a mass without densities does not depend on the design: said so')
finish()
