"""CalculiX's shape sensitivities chained to the design variables: dJ/dX on the deformation's
output points from a ccx run on the variant deck, for ``DesignVariables.totalSensitivity``.

The deck runs a static step and then a sensitivity step (ccx 2.20)::

    *DESIGNVARIABLES, TYPE=COORDINATE     (before the first step)
    surface                               (a node set: the surface nodes the morph moves)
    *STEP
    *STATIC
    ...
    *END STEP
    *STEP
    *SENSITIVITY, WRITE                   (WRITE: the full-precision .sen0 and .sen1 files)
    *DESIGNRESPONSE, NAME=MASS
    MASS
    *DESIGNRESPONSE, NAME=TIP             (one response a card)
    ALL-DISP, load
    *END STEP

What ccx computes (its sources, sensitivity.c and distributesens.f, and finite differences node by
node): for each surface design node i, the derivative raw_i of J with respect to moving that node
alone along its unit normal n_i (the .frd's NORM block), written to JOB.sen1 in the order of the
*DESIGNRESPONSE cards. The .frd's DFDN is raw_i divided by the integral of node i's shape function
over its surface faces (a density per unit area), interpolated from the neighbours at the corner
nodes of quadratic faces, where that integral is zero: not a derivative, so the raw values are
read. Hence dJ/dX_i = raw_i n_i on the surface design nodes, 0 elsewhere; interior nodes are left
out of the design set by ccx. Chained with a morph that moves every node, this leaves out what
moving the interior nodes, sliding the surface nodes along the surface and the averaged normals at
edges change in J: a discretization error that shrinks with the mesh size (Plugin/mlsdeform/README.md, the CalculiX
example's validation against central differences). ccx 2.20's STRAINENERGY coordinate sensitivity
leaves out the change of the elements' volume (objective_shapeener_dx.f) and is 70-80% off.
"""
import os
import re
import warnings

import numpy as np


def _job(frd):
    """The job's files beside its .frd: (folder, job name)."""
    if not frd.endswith('.frd'):
        raise ValueError(f"{frd} is not a ccx result file (.frd)")
    if not os.path.isfile(frd):
        raise ValueError(f"the ccx result file {frd} does not exist")
    return os.path.dirname(os.path.abspath(frd)), os.path.basename(frd)[:-4]


def _responses(folder, job):
    """The design responses of the job's .dat table, in card order: [(type, value, name)]."""
    dat = os.path.join(folder, job + '.dat')
    if not os.path.isfile(dat):
        raise ValueError(f"{dat} does not exist: the .dat file of the run lists its design responses")
    rows, inside = [], False
    with open(dat) as f:
        for line in f:
            if 'D E S I G N   R E S P O N S E' in line:
                inside = True
                continue
            if inside:
                fields = line.split()
                if len(fields) >= 3 and re.fullmatch(r'-?\d\.\d+E[+-]\d+', fields[1]):
                    rows.append((fields[0], float(fields[1]), fields[2]))
    if not rows:
        raise ValueError(f"{dat} lists no design responses: the deck needs a *SENSITIVITY step with *DESIGNRESPONSE cards")
    return rows


def _response_index(folder, job, response):
    rows = _responses(folder, job)
    names = [name.upper() for _, _, name in rows]
    if str(response).upper() not in names:
        raise ValueError(f"the run {os.path.join(folder, job)} has no design response {response!r} "
                         f"(its *DESIGNRESPONSE names: {', '.join(name for _, _, name in rows)})")
    index = names.index(str(response).upper())
    return index, rows[index][0]


def _numbers(path):
    """The rows of a ccx list-directed file (.sen0, .sen1): Fortran 'D' exponents read too."""
    if not os.path.isfile(path):
        raise ValueError(f"{path} does not exist: run the sensitivity step as *SENSITIVITY, WRITE (it writes the "
                         f"full-precision derivatives there)")
    with open(path) as f:
        try:
            return [[float(v) for v in line.replace('D', 'E').split()] for line in f if line.strip()]
        except ValueError as e:
            raise ValueError(f"{path}: {e}") from None


def readCalculixObjective(frd, response):
    """The value of the design response named ``response`` (its *DESIGNRESPONSE NAME) of the ccx run
    whose result file is ``frd``: from JOB.sen0 in full precision (*SENSITIVITY, WRITE), else from
    the .dat table (8 significant digits). Raises ValueError for a missing file or response."""
    folder, job = _job(frd)
    index, _ = _response_index(folder, job, response)
    sen0 = os.path.join(folder, job + '.sen0')
    if os.path.isfile(sen0):
        values = [v for row in _numbers(sen0) for v in row]
        if index < len(values):
            return values[index]
    return _responses(folder, job)[index][1]


def _frd_nodal(frd, normals_needed=True):
    """The .frd's node coordinates and NORM block: ({node: xyz}, {node: normal}). Its data lines are
    fixed-width: ' -1', the node in 10 columns, then 12 columns a value (E12.5, no separator)."""
    coordinates, normals, block = {}, {}, None
    with open(frd) as f:
        for number, line in enumerate(f, start=1):
            code = line[:3]
            if line.startswith('    2C'):
                block = coordinates
            elif code == ' -4':
                block = normals if line[5:13].strip() == 'NORM' else None
            elif code == ' -3':
                block = None
            elif code == ' -1' and block is not None:
                text = line.rstrip('\n')
                try:
                    block[int(text[3:13])] = [float(text[k:k + 12]) for k in (13, 25, 37)]
                except ValueError:
                    raise ValueError(f"{frd}:{number}: not a nodal data line of three values: {text!r}") from None
    if not coordinates:
        raise ValueError(f"{frd} holds no node coordinates (its 2C block): is it a ccx result file?")
    if normals_needed and not normals:
        raise ValueError(f"{frd} holds no NORM block: the run had no *SENSITIVITY step with design variables")
    return coordinates, normals


def _output_rows(deformed, frd):
    """The deformation's output: ({NodeId: output row}, points), checked against the run whose result
    is frd (its node coordinates: the same mesh and shape, to the .frd's 6 significant digits), and
    the .frd's coordinates."""
    from .deformer import deformer as _deformer
    from vtkmodules.util.numpy_support import vtk_to_numpy
    filter_ = _deformer(deformed)
    filter_.update()
    output = filter_.algorithm.GetOutputDataObject(0)
    error = output.GetFieldData().GetAbstractArray('DeformationError') if output is not None else None
    if error is not None and error.GetNumberOfValues() > 0:
        raise RuntimeError(f"the deformation failed: {error.GetValue(0)}")
    ids = output.GetPointData().GetArray('NodeId') if output is not None else None
    if ids is None:
        raise ValueError("the deformation's output has no NodeId point array: its input did not come from the Mesh File reader")
    points = vtk_to_numpy(output.GetPoints().GetData()).astype(np.float64)
    ids = vtk_to_numpy(ids).astype(np.int64)
    row = {int(n): i for i, n in enumerate(ids)}
    coordinates = _frd_nodal(frd, normals_needed=False)[0]
    missing = [n for n in coordinates if n not in row]
    if missing or len(coordinates) != len(row):
        raise ValueError(f"{frd} is a run on another mesh: {len(coordinates)} nodes against the deformation's {len(row)}"
                         + (f", node {missing[0]} not among them" if missing else ""))
    at = np.array([row[n] for n in coordinates])
    scale = float(np.abs(points).max()) or 1.0
    gap = float(np.abs(np.array(list(coordinates.values())) - points[at]).max())
    if gap > 1e-5 * scale:  # E12.5: 6 significant digits, a rounding of at most 5e-6 of a coordinate
        raise ValueError(f"{frd} is a run on another shape: its nodes are up to {gap:.3g} from the deformation's "
                         f"current output points (write the variant deck of the current design and run ccx on it)")
    return row, points, coordinates


def readCalculixSensitivity(deformed, frd, response):
    """dJ/dX as an (n, 3) array in the deformation's output order (as DesignVariables.totalSensitivity
    takes it) for the design response named ``response`` of the ccx run whose result file is
    ``frd``: raw_i n_i at each surface design node (JOB.sen1, the .frd's NORM), 0 at every other
    point (module docstring).

    deformed: the MLS Deform filter (a paraview.simple proxy or the VTK filter) whose input came from
    the Mesh File reader (its NodeId array numbers the output points as the deck numbers its nodes).
    The run must be on the deformation's current shape (its variant deck): the .frd's node
    coordinates are compared with the output points, to its 6 significant digits. Raises ValueError
    naming the file for a missing file, response or NORM block, and for a run on another mesh or
    shape; warns for a STRAINENERGY response (ccx 2.20 leaves out a term of its derivative)."""
    folder, job = _job(frd)
    index, kind = _response_index(folder, job, response)
    if kind.upper() == 'STRAINENERGY':
        warnings.warn("ccx 2.20's coordinate sensitivity of STRAINENERGY leaves out the change of the elements' volume "
                      "(objective_shapeener_dx.f): 70-80% off on the structural example; prefer a displacement response",
                      stacklevel=2)
    row, points, coordinates = _output_rows(deformed, frd)
    normals = _frd_nodal(frd)[1]
    dJdX = np.zeros_like(points)
    for values in _numbers(os.path.join(folder, job + '.sen1')):
        node = int(values[0])
        if node not in row or len(values) <= index + 1:
            raise ValueError(f"{os.path.join(folder, job + '.sen1')}: a row for node {node} that the mesh does not have, "
                             f"or without response {index + 1}")
        normal = np.asarray(normals.get(node, (0.0, 0.0, 0.0)))
        length = float(np.linalg.norm(normal))
        if length > 0:  # a node ccx left without a normal (fully fixed) has no derivative either
            dJdX[row[node]] = values[index + 1] * normal / length
    return dJdX


# The exact path: vtkCalculixSensitivity's responses by name, as exactSensitivity takes them.
EXACT_RESPONSES = {'compliance': 0, 'mass': 1, 'volume': 2, 'displacement': 3, 'all-disp': 4, 'ks-stress': 5}


def _model_text(deck):
    """The main deck's text before its first *STEP, without its model-level *BOUNDARY cards (the
    adjoint load case writes the supports itself, homogeneous)."""
    kept, dropping = [], False
    with open(deck) as f:
        for line in f:
            head = line.lstrip().upper()
            if head.startswith('*') and not head.startswith('**'):
                if re.match(r'\*\s*STEP\b', head):
                    break
                dropping = re.match(r'\*\s*BOUNDARY\b', head) is not None
            if not dropping:
                kept.append(line)
    return ''.join(kept)


def writeAdjointDeck(sensitivity, deck, target):
    """The adjoint load case of the response set up in ``sensitivity`` (a vtkCalculixSensitivity on
    ``deck``): the deck's model (mesh, materials, sections; its includes found from target's folder,
    which must be the deck's), one static step with the supports homogeneous and the loads dJ/du,
    written to target. Raises ValueError with the reason (the deck's, the set's, the result's)."""
    if not sensitivity.ComputeAdjointLoads():
        raise ValueError(sensitivity.GetLastError())
    from vtkmodules.util.numpy_support import vtk_to_numpy
    if os.path.dirname(os.path.abspath(target)) != os.path.dirname(os.path.abspath(deck)):
        raise ValueError(f"the adjoint deck {target} must be beside the deck {deck} (its includes are relative to it)")
    nodes = vtk_to_numpy(sensitivity.GetAdjointLoadNodes())
    loads = vtk_to_numpy(sensitivity.GetAdjointLoads()).reshape(-1, 3)
    supports = zip(vtk_to_numpy(sensitivity.GetSupportNodes()), vtk_to_numpy(sensitivity.GetSupportDofs()))
    lines = [_model_text(deck), '*STEP\n*STATIC\n*BOUNDARY\n']
    lines += ['%d, %d, %d, 0.\n' % (n, d, d) for n, d in supports]
    lines.append('*CLOAD\n')  # (ccx reads at most 20 characters a field: 14 significant digits)
    lines += ['%d, %d, %.13e\n' % (n, d + 1, v[d]) for n, v in zip(nodes, loads) for d in range(3) if v[d] != 0]
    lines.append('*NODE FILE, DOUBLE\nU\n*END STEP\n')  # (full precision)
    partial = target + '.writing-%d' % os.getpid()
    with open(partial, 'w') as f:
        f.write(''.join(lines))
    os.replace(partial, target)
    return target


def _run_ccx(deck, ccx, threads):
    import subprocess
    folder, name = os.path.split(os.path.abspath(deck))
    job = os.path.splitext(name)[0]
    env = dict(os.environ, **({'OMP_NUM_THREADS': str(threads)} if threads else {}))
    result = subprocess.run([ccx, '-i', job], cwd=folder, capture_output=True, text=True, env=env)
    log = result.stdout + result.stderr
    if result.returncode != 0 or '*ERROR' in log:
        raise RuntimeError(f'ccx failed on {deck}:\n' + log[-2000:])
    return os.path.join(folder, job + '.frd')


def exactSensitivity(deformed, deck, frd, response, set=None, direction=(0.0, 0.0, 1.0), ks_weight=50.0, reference_stress=1.0,
                     adjoint_frd=None, ccx='ccx', threads=None):
    """(J, dJ/dX): the response of the ccx run of ``deck`` (the deformation's current variant deck)
    whose result is ``frd``, and its exact shape gradient, an (n, 3) array in the deformation's
    output order for DesignVariables.totalSensitivity: three components at every node, interior and
    midside nodes too (vtkCalculixSensitivity: dJ/dX = dJ/dX|_u - lambda^T d(K u)/dX, element by
    element as ccx integrates it).

    response: 'compliance' (the point loads' work f . u), 'mass' or 'volume' (of the element set
    ``set``, default all elements), 'displacement' (the sum of direction . u over the node set
    ``set``), 'all-disp' (ccx's ALL-DISP over the node set: sqrt(sum |u|^2)) or 'ks-stress' (the KS
    aggregate of the von Mises stresses at the integration points of the element set ``set``,
    default all: m + (S / rho) ln sum exp(rho (sigma - m) / S), m the largest, S
    ``reference_stress``, rho ``ks_weight``: at most S ln(N) / rho above the largest of the N
    points' stresses). The last three need the adjoint load case: written beside the deck as JOB-adjoint.inp and solved by ``ccx`` (unless
    its result ``adjoint_frd`` is given). The deck needs *NODE FILE with U in its static step.
    Raises ValueError with the reason for an unknown response or set, a run on another mesh or
    shape, a result without U, and what the analysis does not support (the keyword named, e.g.
    NLGEOM); RuntimeError for a failed ccx run of the adjoint deck."""
    key = str(response).lower()
    if key not in EXACT_RESPONSES:
        raise ValueError(f"unknown response {response!r} (known: {', '.join(EXACT_RESPONSES)})")
    from .deformer import _load_wrapping
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from .deformer import deformer as _deformer
    filter_ = _deformer(deformed)
    filter_.update()
    output = filter_.algorithm.GetOutputDataObject(0)
    ids = output.GetPointData().GetArray('NodeId') if output is not None else None
    if ids is None:
        raise ValueError("the deformation's output has no NodeId point array: its input did not come from the Mesh File reader")
    points = vtk_to_numpy(output.GetPoints().GetData()).astype(np.float64)
    row = {int(n): i for i, n in enumerate(vtk_to_numpy(ids))}
    s = _load_wrapping(readers=True).vtkCalculixSensitivity()
    s.SetDeckFileName(os.path.abspath(deck))
    s.SetResultFileName(os.path.abspath(frd))
    s.SetResponse(EXACT_RESPONSES[key])
    s.SetResponseSet(set or '')
    s.SetDirection(*[float(v) for v in direction])
    if not (ks_weight > 0 and reference_stress > 0):
        raise ValueError(f"ks_weight ({ks_weight}) and reference_stress ({reference_stress}) must be positive")
    s.SetKSWeight(float(ks_weight))
    s.SetReferenceStress(float(reference_stress))
    if s.NeedsAdjoint():
        if adjoint_frd is None:
            adjoint = writeAdjointDeck(s, deck, os.path.splitext(os.path.abspath(deck))[0] + '-adjoint.inp')
            adjoint_frd = _run_ccx(adjoint, ccx, threads)
        s.SetAdjointResultFileName(os.path.abspath(adjoint_frd))
    if not s.Compute():
        raise ValueError(s.GetLastError())
    gradient = vtk_to_numpy(s.GetGradient()).reshape(-1, 3)
    ids = vtk_to_numpy(s.GetNodeIds())
    if len(ids) != len(row) or any(int(n) not in row for n in ids):
        raise ValueError(f"the deck {deck} has {len(ids)} nodes, not the deformation's output's {len(row)}: another mesh")
    at = np.array([row[int(n)] for n in ids])
    gap = float(np.abs(vtk_to_numpy(s.GetNodeCoordinates()).reshape(-1, 3) - points[at]).max())
    if gap > 1e-9 * (float(np.abs(points).max()) or 1.0):  # the variant deck holds the output's coordinates
        raise ValueError(f"the deck {deck} is another shape: its nodes are up to {gap:.3g} from the deformation's current "
                         f"output points (write the variant deck of the current design and run ccx on it)")
    dJdX = np.zeros_like(points)
    dJdX[at] = gradient
    return s.GetValue(), dJdX
