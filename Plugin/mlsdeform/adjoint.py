"""OpenFOAM's adjoint surface sensitivities as dJ/dX on the deformation's points, and the objective
value, for the design-optimization loop:

    dJdX = mlsdeform.readFoamSensitivity(deformed, field='pointSensVecadjS1ESI', time='latest')
    g = dvs.totalSensitivity(dJdX)                       # {'name': dJ/dp, ...}
    J = mlsdeform.readFoamObjective(case)

What adjointOptimisationFoam (v1912) writes, from its sources (sensitivitySurfacePoints and
sensitivitySurface of src/optimisation/adjointOptimisation):

- ``surfacePoints`` sensitivities are point fields over every mesh point, zero away from the
  sensitivity patches: ``pointSensVec<solver>`` (vector), ``pointSensNormal<solver>`` (its
  component along the point's normal: the normalized sum of the unit normals of the point's patch
  faces, pointing out of the fluid) and ``pointSensNormalVec<solver>`` (that component times the
  normal). The solver first assembles the total derivative dJ/dx_p of every patch point; with
  ``includeSurfaceArea false`` (its default for surfacePoints) it divides it by A_p, the summed
  area of the point's patch faces, and it writes the vector forms only with
  ``writeAllSurfaceFiles true``.
- ``surface`` sensitivities are face fields (patch values of a vol field: ``faceSensVec<solver>``,
  ``faceSensNormal<solver>``, ``faceSensNormalVec<solver>``), the derivative per face with the
  face's area included (``includeSurfaceArea true`` is that type's default), the normal pointing
  out of the fluid. A face's value is shared equally by its points (dJ/dx_p = sum over the
  point's faces of v_f / number of the face's points: the face centre moves with the mean of its
  points). These fields leave out how a face's area and normal change with its points (the point
  form's dSf/dx and dnf/dx terms): on the NACA 0012 validation they gave 0.3 to 0.65 of the finite
  differences where pointSensVec gave 1.02, so reading one warns.

readFoamSensitivity reads the case's ``system/optimisationDict`` for the type, the patches and
includeSurfaceArea, and undoes the area division, so that every form gives dJ/dX; a normal form
drops the tangential part (which is zero for the continuous shape derivative).
"""
import glob
import math
import os
import re

import numpy as np

from .deformer import case_path
from .ranks import all_reduce, rank

SENSITIVITY_PREFIXES = ('pointSensVec', 'pointSensNormalVec', 'pointSensNormal',
                        'faceSensVec', 'faceSensNormalVec', 'faceSensNormal')


# -- OpenFOAM dictionaries ---------------------------------------------------------------------
def _tokens(text):
    text = re.sub(r'/\*.*?\*/', ' ', text, flags=re.S)
    text = re.sub(r'//[^\n]*', ' ', text)
    return re.findall(r'"[^"]*"|[{}();]|[^\s{}();]+', text)


def readFoamDictionary(path):
    """An OpenFOAM dictionary file as nested Python dicts (values: a string, or a list of strings
    for a parenthesized list; a keyword with several words keeps them as a list)."""
    with open(path) as f:
        tokens = _tokens(f.read())
    position = 0

    def value_until_semicolon():
        nonlocal position
        words = []
        while position < len(tokens) and tokens[position] != ';':
            token = tokens[position]
            position += 1
            if token == '(':
                items = []
                depth = 1
                while depth:
                    t = tokens[position]
                    position += 1
                    depth += (t == '(') - (t == ')')
                    if depth and t not in '()':
                        items.append(t.strip('"'))
                words.append(items)
            else:
                words.append(token.strip('"'))
        position += 1
        return words[0] if len(words) == 1 else words

    def dictionary():
        nonlocal position
        result = {}
        while position < len(tokens) and tokens[position] != '}':
            key = tokens[position].strip('"')
            position += 1
            if position < len(tokens) and tokens[position] == '{':
                position += 1
                result[key] = dictionary()
                position += 1
            else:
                result[key] = value_until_semicolon()
        return result

    return dictionary()


def _sensitivity_settings(case):
    path = os.path.join(case, 'system', 'optimisationDict')
    if not os.path.isfile(path):
        raise ValueError(f"{case} has no system/optimisationDict: it is not an adjointOptimisationFoam case")
    try:
        settings = readFoamDictionary(path)['optimisation']['sensitivities']
        kind = settings['type']
        patches = settings['patches']
    except (KeyError, IndexError, TypeError) as e:
        raise ValueError(f"{path}: no optimisation.sensitivities type and patches ({e})") from None
    patches = [patches] if isinstance(patches, str) else list(patches)
    default_area = kind != 'surfacePoints'  # the two types' defaults in v1912
    area = str(settings.get('includeSurfaceArea', 'true' if default_area else 'false')).lower() in ('true', 'on', 'yes', '1')
    return kind, patches, area


# -- the case's times and the objective --------------------------------------------------------
def _case_folder(case):
    case = os.path.abspath(case)
    return os.path.dirname(case) if os.path.isfile(case) else case


def _times(case):
    times = []
    for entry in os.listdir(case):
        try:
            value = float(entry)
        except ValueError:
            continue
        if os.path.isdir(os.path.join(case, entry)) and math.isfinite(value):
            times.append((value, entry))
    return sorted(times)


def _field_time(case, field, time):
    """The time folder (its name) that holds field: the latest one with it, or the one asked for."""
    def has(folder):
        return any(os.path.isfile(os.path.join(case, folder, field + ext)) for ext in ('', '.gz'))
    times = _times(case)
    if time == 'latest':
        holding = [name for _, name in times if has(name)]
        if holding:
            return holding[-1]
        found = sorted({os.path.basename(p).replace('.gz', '') for _, name in times
                        for p in glob.glob(os.path.join(case, name, '*Sens*'))})
        decomposed = glob.glob(os.path.join(case, 'processor*', '*', field + '*'))
        raise ValueError(f"no time of {case} holds the field {field!r}"
                         + (f" (its processor folders do: run reconstructPar -fields '({field})' first)" if decomposed else
                            f" (sensitivity fields there: {', '.join(found)})" if found else
                            " (no sensitivity field at all: has adjointOptimisationFoam run in it?)"))
    for value, name in times:
        if name == str(time) or math.isclose(value, float(time), rel_tol=1e-12, abs_tol=1e-12):
            if has(name):
                return name
            raise ValueError(f"time {name} of {case} has no field {field!r}")
    raise ValueError(f"{case} has no time {time!r} (times: {', '.join(n for _, n in times) or 'none'})")


def readFoamObjective(case, objective=None):
    """The objective value J of the last primal solution of an adjointOptimisationFoam run: the
    last row of optimisation/objective/<time>/<objective><adjoint solver> (the objective's name
    and its adjoint solver's, e.g. 'dragadjS1'; by default the only such file)."""
    case = _case_folder(case)
    folders = [os.path.join(case, 'optimisation', 'objective', name)
               for _, name in _times(os.path.join(case, 'optimisation', 'objective'))] \
        if os.path.isdir(os.path.join(case, 'optimisation', 'objective')) else []
    if not folders:
        raise ValueError(f"{case} has no optimisation/objective history: has adjointOptimisationFoam run in it?")
    files = sorted(f for f in os.listdir(folders[-1]) if 'Instant' not in f and not f.startswith('.'))
    if objective is not None:
        files = [f for f in files if f == objective]
    if len(files) != 1:
        raise ValueError(f"{folders[-1]}: objective {objective!r} is not one of {files}" if objective else
                         f"{folders[-1]} holds several objectives {files}: name one")
    with open(os.path.join(folders[-1], files[0])) as f:
        rows = [line.split() for line in f if line.strip() and not line.startswith('#')]
    if not rows or len(rows[-1]) < 2:
        raise ValueError(f"{os.path.join(folders[-1], files[0])} holds no value")
    return float(rows[-1][1])


# -- reading a case as ParaView's reader does --------------------------------------------------
def _leaves(data):
    """(name, dataset) of every non-empty leaf of a dataset or composite dataset, in the order a
    composite iterator visits them (the output order of MLS Deform's sensitivities)."""
    if not data.IsA('vtkCompositeDataSet'):
        return [('', data)]
    leaves = []
    iterator = data.NewIterator()
    iterator.InitTraversal()
    while not iterator.IsDoneWithTraversal():
        meta = iterator.GetCurrentMetaData()
        name = meta.Get(data.NAME()) if meta is not None and meta.Has(data.NAME()) else ''
        leaves.append((name, iterator.GetCurrentDataObject()))
        iterator.GoToNextItem()
    return leaves


def _points(dataset):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    points = dataset.GetPoints()
    return vtk_to_numpy(points.GetData()).reshape(-1, 3) if points is not None else np.zeros((0, 3), np.float32)


def _read_case(case, patches=(), field=None, time=None, kind=None):
    """The case's internal mesh points (float32, as the reader gives them), the field (kind 'point':
    its values at the mesh points; 'face': per patch face; None: no field) and the patches' faces
    (point ids of the internal mesh), at time (None: the reader's first)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from .vtkfoam import configured_reader
    foam, made = _foam_file(case)
    try:
        reader = configured_reader(foam, patches, decompose_polyhedra=False, fields=[field] if kind else [])
        if time is None:
            reader.Update()
        else:
            reader.UpdateTimeStep(float(time))
        blocks = dict(_leaves(reader.GetOutput()))
        internal = blocks.get('internalMesh')
        if internal is None:
            raise ValueError(f"{case}: the OpenFOAM reader gave no internal mesh")
        mesh = np.array(_points(internal))
        faces = []   # per patch: (point ids per face, field values per face or None)
        for patch in patches:
            block = blocks[patch]
            ids = _match(mesh, _points(block))
            cells = [[ids[block.GetCell(c).GetPointId(k)] for k in range(block.GetCell(c).GetNumberOfPoints())]
                     for c in range(block.GetNumberOfCells())]
            values = None
            if kind == 'face':
                array = block.GetCellData().GetArray(field)
                if array is None:
                    raise ValueError(f"the face field {field!r} has no values on patch {patch!r} of {case}")
                values = np.array(vtk_to_numpy(array), dtype=float)
            faces.append((cells, values))
        values = None
        if kind == 'point':
            array = internal.GetPointData().GetArray(field)
            if array is None:
                raise ValueError(f"{case}: the reader did not read the point field {field!r} at time {time}")
            values = np.array(vtk_to_numpy(array), dtype=float)
        return mesh, values, faces
    finally:
        if made:
            os.remove(foam)


def _foam_file(case):
    """A .foam file of the case for ParaView's reader: its own, or an empty one made for the read
    (removed after it); (path, made)."""
    own = sorted(glob.glob(os.path.join(case, '*.foam')))
    if own:
        return own[0], False
    path = os.path.join(case, '.mlsdeform-sensitivity.foam')
    open(path, 'a').close()
    return path, True


def _match(reference, query):
    """For each row of query, the index of the row of reference with the same coordinates (the
    same float32 values: both read from one points file by the same reader), or -1."""
    reference = np.ascontiguousarray(reference, dtype=np.float32)
    query = np.ascontiguousarray(query, dtype=np.float32)
    key = np.dtype((np.void, 12))
    both = np.concatenate([reference, query]).view(key).ravel()
    _, first, inverse = np.unique(both, return_index=True, return_inverse=True)
    ids = first[inverse[len(reference):]]
    ids[ids >= len(reference)] = -1
    return ids


def _face_geometry(mesh, cells):
    """Each face's vector area (OpenFOAM's Sf: the sum of its triangles' vector areas, the same
    about any fan point) as an array."""
    areas = np.zeros((len(cells), 3))
    for f, ids in enumerate(cells):
        x = mesh[ids].astype(float)
        areas[f] = 0.5 * np.cross(x, np.roll(x, -1, axis=0)).sum(axis=0)
    return areas


def _mesh_gradient(mesh, values, faces, kind, area_included, normal_form):
    """dJ/dx at the mesh points (N x 3) from the field, undoing the solver's area division and
    turning a normal form into a vector (module docstring)."""
    n = len(mesh)
    gradient = np.zeros((n, 3))
    normals = np.zeros((n, 3))    # sum of the unit normals of the point's patch faces
    point_area = np.zeros(n)      # A_p: the summed area of the point's patch faces
    for cells, face_values in faces:
        Sf = _face_geometry(mesh, cells)
        magSf = np.linalg.norm(Sf, axis=1)
        for f, ids in enumerate(cells):
            normals[ids] += Sf[f] / magSf[f]
            point_area[ids] += magSf[f]
            if kind == 'face':
                v = face_values[f] if face_values[f].ndim else face_values[f] * Sf[f] / magSf[f]
                gradient[ids] += (v if area_included else v * magSf[f]) / len(ids)
    if kind == 'point':
        if values.ndim == 1:
            if not normal_form:
                raise ValueError("a scalar point field must be a normal sensitivity (pointSensNormal...)")
            length = np.linalg.norm(normals, axis=1)
            unit = np.divide(normals, length[:, None], out=np.zeros_like(normals), where=length[:, None] > 0)
            gradient = values[:, None] * unit
        else:
            gradient = values.copy()
        if not area_included:
            gradient *= point_area[:, None]
    return gradient


# -- the public entry --------------------------------------------------------------------------
def readFoamSensitivity(deformed, field='pointSensVecadjS1ESI', time='latest', case=None, source=None):
    """dJ/dX as an (n, 3) array in the deformation's output order (as DesignVariables.totalSensitivity
    takes it) from an adjointOptimisationFoam sensitivity field of an OpenFOAM case.

    deformed: the MLS Deform proxy whose input came from ParaView's OpenFOAM reader. case: the
    case folder (or its .foam file) the adjoint ran in, whose mesh must be the deformation's current
    output (the variant written from it, or the source case itself while every design variable is at
    its undeformed value); default: the deformation's source case (the reader's CasePath). field:
    a point or face sensitivity field (module docstring); time: 'latest' (the latest time that
    holds the field) or a time. source: the deformation's source case, needed where its input lost
    the reader's CasePath (after RedistributeDataSet). Each polyMesh point's dJ/dx goes to the
    first output point at that position (the internal mesh's, or a patch's when the internal mesh
    is not deformed); every other output point gets zero, so that no point counts twice. Under MPI
    (pvbatch --symmetric) every process reads the case and gets its own output points' rows; a
    point on several processes' pieces counts on the lowest-ranked one, so that
    DesignVariables.totalSensitivity's sum over the processes is the serial one. Raises ValueError naming the field
    or case for a missing field, time or optimisationDict, a field of the wrong size or that is not
    a sensitivity, a case whose mesh is not the deformation's input or its current shape, and a
    field that is zero at every point a Handle region moves.
    """
    from .deformer import deformer as _deformer
    filter_ = _deformer(deformed)
    algorithm = filter_.algorithm
    filter_.update()
    source_data = algorithm.GetInputDataObject(0, 0)
    output = algorithm.GetOutputDataObject(0)
    if source_data is None or output is None:
        raise RuntimeError("the MLS Deform filter has no input or output")
    error = output.GetFieldData().GetAbstractArray('DeformationError')
    if error is not None and error.GetNumberOfValues() > 0:
        raise RuntimeError(f"the deformation failed: {error.GetValue(0)}")
    path = case_path(source_data)
    if source is not None:
        source = _case_folder(source)
    elif path:
        source = os.path.abspath(path)
    else:
        raise ValueError("the deformation's input has no CasePath field data (it did not come from the OpenFOAM reader, "
                         "or RedistributeDataSet dropped it): give source=, the case it was read from")
    case = source if case is None else _case_folder(case)
    if not os.path.isdir(case):
        raise ValueError(f"the case {case} does not exist")
    prefix = next((p for p in SENSITIVITY_PREFIXES if field.startswith(p)), None)
    if prefix is None:
        raise ValueError(f"{field!r} is not a sensitivity field of adjointOptimisationFoam (its name starts with one of "
                         f"{', '.join(SENSITIVITY_PREFIXES)})")
    kind = 'point' if prefix.startswith('point') else 'face'
    if kind == 'face':
        import warnings
        warnings.warn(f"{field}: the face sensitivities of adjointOptimisationFoam's `surface` type leave out how a face's "
                      "area and normal change with its points; on the NACA 0012 validation their dJ/dp was 0.3-0.65 of the "
                      "finite differences (Plugin/mlsdeform/README.md): prefer `type surfacePoints` and its pointSensVec field", stacklevel=2)
    sensitivity_type, patches, area_included = _sensitivity_settings(case)
    folder = _field_time(case, field, time)
    mesh, values, faces = _read_case(case, patches, field, folder, kind)
    if kind == 'point' and len(values) != len(mesh):
        raise ValueError(f"{field!r} at time {folder} of {case} has {len(values)} values but the mesh has {len(mesh)} points")
    if kind == 'point' and (values.ndim == 1) != (prefix == 'pointSensNormal'):
        raise ValueError(f"{field!r} at time {folder} of {case} is a {'scalar' if values.ndim == 1 else 'vector'} field, "
                         f"which a {prefix} field is not")
    if not all(np.all(np.isfinite(v)) for v in ([values] if values is not None else []) + [fv for _, fv in faces if fv is not None]):
        raise ValueError(f"{field!r} at time {folder} of {case} has values that are not finite")
    gradient = _mesh_gradient(mesh, values, faces, kind, area_included, 'Normal' in prefix and 'NormalVec' not in prefix)

    # the deformation's points: their input positions (the source case's float32 points) and now
    leaves = [points for points in (_points(d) for _, d in _leaves(source_data))]
    inputs = np.concatenate(leaves) if leaves else np.zeros((0, 3), np.float32)
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.util.numpy_support import vtk_to_numpy
    now = vtkDoubleArray()
    if not algorithm.GetDeformedPoints(now):
        raise RuntimeError(algorithm.GetSensitivityError())
    now = vtk_to_numpy(now).reshape(-1, 3)
    if len(now) != len(inputs):
        raise RuntimeError(f"the output has {len(now)} points but the input {len(inputs)}")
    ids = _match(mesh if case == source else _source_points(source, len(mesh)), inputs)
    if all_reduce(np.count_nonzero(ids >= 0), 'sum') == 0:
        raise ValueError(f"no point of the deformation's input is a mesh point of {source}")
    # each mesh point once: at its first output point, on the lowest-ranked process that has it
    order = np.flatnonzero(ids >= 0)
    _, first = np.unique(ids[order], return_index=True)
    owners = order[first]
    holder = np.full(len(mesh), np.iinfo(np.int32).max, dtype=np.int64)
    holder[ids[owners]] = rank()
    owners = owners[all_reduce(holder, 'min')[ids[owners]] == rank()]
    mesh_ids = ids[owners]  # not every mesh point need be deformed (e.g. the patches only)
    # the case's mesh must be the deformation's current shape (float32 round-off of its points);
    # the mesh's diagonal: the same bound on every process
    diagonal = float(np.linalg.norm(mesh.max(axis=0).astype(float) - mesh.min(axis=0))) if len(mesh) else 1.0
    gap = all_reduce(float(np.abs(mesh[mesh_ids].astype(float) - now[owners]).max()) if len(owners) else 0.0, 'max')
    if gap > 1e-6 * diagonal:
        raise ValueError(f"the mesh of {case} is not the deformation's current shape (a point is {gap:.3g} away, "
                         f"{gap / diagonal:.2g} of the diagonal): run the adjoint on the variant written from the "
                         f"deformation at the current design variables, or set the variables the case was written with")
    result = np.zeros((len(inputs), 3))
    result[owners] = gradient[mesh_ids]
    _check_on_handles(filter_, result, inputs, field, case, patches)
    return result


def _source_points(source, n):
    """The source case's polyMesh points as the reader gives them (float32), for the matching."""
    points = _read_case(source)[0]
    if len(points) != n:
        raise ValueError(f"the sensitivity case's mesh has {n} points but the deformation's source {source} {len(points)}: "
                         "it is not a variant of it")
    return points


def _check_on_handles(filter_, gradient, inputs, field, case, patches):
    """A field that is zero wherever a Handle region moves gives dJ/dp = 0 for every variable: an error."""
    from .deformer import _load_wrapping
    handles = [r for r in filter_.regions() if filter_.role(r) == _load_wrapping().vtkConstraintRegion.Handle]
    if not handles:
        raise ValueError("the deformation has no Handle region: no design variable can move a point")
    held = [np.array(_points(d)) for r in handles for _, d in _leaves(filter_.output(r))]
    moving = np.zeros(len(inputs), bool)
    if held:
        ids = _match(inputs, np.concatenate(held))
        moving[ids[ids >= 0]] = True
    if not all_reduce(int(np.any(np.abs(gradient[moving]).sum(axis=1) > 0)), 'max'):
        where = all_reduce(np.count_nonzero(np.abs(gradient).sum(axis=1) > 0), 'sum')
        raise ValueError(f"{field!r} of {case} is zero at every point of the Handle regions (it is non-zero at {where} "
                         f"point(s), none of them a Handle region's; its optimisationDict names the patches {patches}): "
                         f"dJ/dp would be zero")
