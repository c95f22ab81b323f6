"""The plate's structural design loop on a plain VTK pipeline (Debian's python3 with the plugin's
folder on sys.path, or pvpython): the deck read by the Mesh File reader, MLS Deform with the holes
and the fillet as handle bodies (their sets), the clamped end and the tip fixed and the plane faces
slipping in their planes (the plate keeps its thickness and width), design
variables on them, and for a design: its variant deck written, ccx run on it, the responses and
their dJ/dp through the exact structural gradient (mlsdeform.exactSensitivity, exact=True) or
CalculiX's own normal-only shape sensitivities (mlsdeform.readCalculixSensitivity).

    design = PlateDesign(source_deck, work_folder)
    J, dJdp, quality = design.evaluate({'x1': 0.2, 'r1': -0.1})

validate(design, steps) compares dJ/dp with central differences of ccx's responses (two more ccx
runs a variable and step), the check the README reports.
"""
import os

import mlsdeform
from mlsdeform import meshfile, vtkfoam
import plate

# The responses of the plate's sensitivity step: its mass, and the norm of the loaded end's
# displacement (ALL-DISP over the tip nodes, which the morph keeps fixed).
RESPONSES = (('MASS', 'MASS'), ('TIP', 'ALL-DISP, tip'))

# The design variables: translate= a direction in mm per unit, scale= an axis along which the
# body's scale factor grows by p times its length (a hole's radius by p), rotate= degrees per unit
# about an axis through the body's pivot. The fillets slide along the plate (their arcs moved
# along x: the rounded corners cut deeper or less deep into the loaded end).
VARIABLES = {
    'x1': dict(bodies=['hole1'], translate=[1, 0, 0], lower=-0.5, upper=0.5),
    'y1': dict(bodies=['hole1'], translate=[0, 1, 0], lower=-0.4, upper=0.4),
    'r1': dict(bodies=['hole1'], scale=[1, 1, 0], lower=-0.2, upper=0.2),
    'x2': dict(bodies=['hole2'], translate=[1, 0, 0], lower=-0.5, upper=0.3),
    'r2': dict(bodies=['hole2'], scale=[1, 1, 0], lower=-0.2, upper=0.2),
    'fillet': dict(bodies=['fillet'], translate=[1, 0, 0], lower=-0.2, upper=0.2),
    'turn': dict(bodies=['holes'], rotate=[0, 0, 1], lower=-10, upper=10),
}


# The responses by the exact path (mlsdeform.exactSensitivity): its response and set; the
# compliance (the loads' work f . u) has no ccx sensitivity card here.
EXACT = {'MASS': ('mass', None), 'TIP': ('all-disp', 'tip'), 'COMPLIANCE': ('compliance', None)}


def make_source(folder, size=0.5, holes=((3.0, 1.5, 0.7), (7.0, 2.5, 0.7)), fillet=0.8, responses=RESPONSES, exact=False):
    """The plate deck (plate.py): folder/plate.inp, with ccx's sensitivity step for the responses,
    or (exact) without it and with the displacements in full precision for the exact path."""
    plate.mesh_plate(folder, holes=holes, size=size, fillet=fillet)
    return plate.write_analysis(folder, responses=() if exact else responses, double=exact)


class PlateDesign:
    """MLS Deform of the source deck with the variables named (VARIABLES' keys), or given as
    {name: specification} in VARIABLES' form, where a specification with 'local' (addLocalDV's
    count/points, direction, axis, mirror) makes local shape variables name_0, name_1, ... on its
    one body; the bodies are one Handle region each, 'holes' both holes as one body (one pivot: a
    rotation moves them about their common centre). fixed: the sets the morph holds in place."""

    def __init__(self, deck, work, variables=('x1', 'r1', 'x2', 'r2', 'fillet'), responses=RESPONSES, exact=False,
                 fixed=('fixed', 'tip'), **settings):
        """exact: J and dJ/dX by mlsdeform.exactSensitivity (the deck of make_source(exact=True));
        otherwise ccx's responses and its own normal-only sensitivities."""
        self.deck, self.work, self.response_cards, self.exact = deck, work, responses, exact
        self.reader = meshfile.open_mesh(deck)
        specifications = variables if isinstance(variables, dict) else {name: VARIABLES[name] for name in variables}
        bodies = []
        for specification in specifications.values():
            bodies += [b for b in specification['bodies'] if b not in bodies]
        sets = {'holes': ['hole1', 'hole2']}
        self.deform = vtkfoam.morph(self.reader, {b: sets.get(b, [b]) for b in bodies}, (0, 0, 0),
                                    fixed=list(fixed), slip=['bottom', 'top', 'front', 'back'], **settings)
        region = {b: self.deform.GetInputAlgorithm(1, i) for i, b in enumerate(bodies)}  # morph connects the bodies first
        self.dvs = mlsdeform.DesignVariables(self.deform)
        for name, specification in specifications.items():
            v = dict(specification)
            on = [region[b] for b in v.pop('bodies')]
            if 'local' in v:
                self.dvs.addLocalDV(name, on[0], **v.pop('local'), **v)
            else:
                self.dvs.addHandleDV(name, on, **v)
        self.runs = 0

    def write(self, values, name):
        """The variant deck of a design: work/name/plate.inp; returns it and the mesh figures."""
        self.dvs.setDesignVars(values)
        self.dvs._updated()
        quality = mlsdeform.meshQuality(self.dvs)
        target = os.path.join(self.work, name, os.path.basename(self.deck))
        meshfile.save_variant(self.deform, target, overwrite=True)
        return target, quality

    def responses(self, values, name):
        """ccx on the design's variant: ({response: J}, frd, quality). Raises RuntimeError, without
        running ccx, for a design that inverts elements (the FEM verdict)."""
        deck, quality = self.write(values, name)
        if quality['InvertedCells'] != 0:
            raise RuntimeError(f"the design {values} inverts {quality['InvertedCells']} elements (least scaled Jacobian "
                               f"{quality['MinScaledJacobian']:.3f}): its variant {deck} is not run")
        plate.run_ccx(deck)
        self.runs += 1
        frd = deck[:-4] + '.frd'
        if self.exact:
            self.exact_gradients = {}
            J = {}
            for r, _ in self.response_cards:
                response, subset = EXACT[r]
                J[r], self.exact_gradients[r] = mlsdeform.exactSensitivity(self.deform, deck, frd, response, set=subset)
                self.runs += 1 if response == 'all-disp' else 0  # its adjoint run
            return J, frd, quality
        return {r: mlsdeform.readCalculixObjective(frd, r) for r, _ in self.response_cards}, frd, quality

    def evaluate(self, values, name='design'):
        """({response: J}, {response: {variable: dJ/dp}}, quality) of a design."""
        J, frd, quality = self.responses(values, name)
        dJdX = self.exact_gradients if self.exact else {r: mlsdeform.readCalculixSensitivity(self.deform, frd, r) for r, _ in self.response_cards}
        return J, {r: self.dvs.totalSensitivity(dJdX[r]) for r, _ in self.response_cards}, quality


def validate(design, steps, at=None, variables=None):
    """For each variable (default: all): dJ/dp by the chain (ccx's sensitivities through dX/dp) and
    by central differences (J(p + h) - J(p - h)) / 2h of ccx's responses for each step h, at the
    design at (default: every variable 0). Returns rows (variable, response, chain, {h: difference})."""
    at = dict(at or {name: 0.0 for name in design.dvs.getVarNames()})
    _, gradients, _ = design.evaluate(at, 'validate-base')
    rows = []
    for name in variables or design.dvs.getVarNames():
        differences = {}
        for h in steps:
            plus, _, _ = design.responses(dict(at, **{name: at[name] + h}), 'validate-plus')
            minus, _, _ = design.responses(dict(at, **{name: at[name] - h}), 'validate-minus')
            differences[h] = {r: (plus[r] - minus[r]) / (2 * h) for r, _ in design.response_cards}
        for r, _ in design.response_cards:
            rows.append((name, r, gradients[r][name], {h: differences[h][r] for h in steps}))
    design.dvs.setDesignVars(at)
    return rows


def table(rows):
    """The validation's rows as a markdown table: the chain, the central differences, the gap to the
    smaller step's difference, relative to it and to the response's largest derivative (a variable
    that hardly changes J has a large relative gap that matters little to a gradient)."""
    steps = sorted(rows[0][3], reverse=True)
    largest = {}
    for _, response, _, differences in rows:
        largest[response] = max(largest.get(response, 0.0), abs(differences[steps[-1]]))
    lines = ['| variable | response | dJ/dp (chained) | ' + ' | '.join('central difference, h = %g' % h for h in steps) +
             ' | gap | gap / largest |', '|---|---|---|' + '---|' * len(steps) + '---|---|']
    for name, response, chain, differences in rows:
        fd = differences[steps[-1]]
        relative = '%+.1f%%' % (100 * (chain - fd) / abs(fd)) if abs(fd) > 1e-3 * largest[response] else 'J unchanged'
        lines.append('| %s | %s | %.6g | %s | %s | %+.1f%% |' % (
            name, response, chain, ' | '.join('%.6g' % differences[h] for h in steps), relative,
            100 * (chain - fd) / largest[response]))
    return '\n'.join(lines)
