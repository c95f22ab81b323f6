"""Design of experiments on an OpenFOAM case or an FEM deck: a Latin hypercube in the design
variables' bounds, or a table of values, turned into variants with a mesh-quality verdict each.

    report = mlsdeform.designOfExperiments(dvs, 'variants', samples=50, seed=0)
    report = mlsdeform.designOfExperiments(dvs, 'variants', table='doe.csv')

On an OpenFOAM case every variant is ``<folder>/variant<i>/case.foam``, written by the plugin's
OpenFOAM case writer (mlsdeform.foam's for a paraview.simple proxy, mlsdeform.vtkfoam's for a VTK
filter) from the deformation's source case (the reader's CasePath): its own points, and links to
the source's unchanged files unless copies are asked for; the verdict is checkMesh's
(THRESHOLDS: InvertedCells, MaxNonOrthogonality, MaxSkewness at most their thresholds). On a
solver's mesh file read by the Mesh File reader (a deck, a Gmsh mesh) every variant is
``<folder>/variant<i>/<the file's name>`` (a deck's included files beside it), only the node
coordinates changed (mlsdeform.meshfile); a structural solver's mesh gets an FEM solver's verdict
(FEM_THRESHOLDS: no inverted element, and the least scaled Jacobian over every element's corners
and integration points at least MinScaledJacobian), a finite-volume solver's checkMesh's. ``<folder>/report.csv`` holds a row per variant: the
variables' values, the verdict's figures (MLS Deform's mesh-quality figures), ok (the verdict),
seconds and path (empty for a variant that failed and was not written). ``<folder>/design.json``
records the design (the values, and the source, regions and set-up it deforms with), so that
running the same call again resumes: rows already in the report are kept, a variant interrupted
while it was written (its ``.writing-*`` files) is written again, and a different design in the
same folder is an error that says what differs.
"""
import csv
import json
import math
import os
import shutil
import time

import numpy as np

# DAFoam's checkMeshThreshold defaults: a variant of a case passes with at most these figures.
THRESHOLDS = {'MaxNonOrthogonality': 70.0, 'MaxSkewness': 4.0, 'InvertedCells': 0}
# A variant of an FEM deck passes with no inverted element and every element's scaled Jacobian
# (at its corners and integration points) at least MinScaledJacobian: 0.1 by default, below which
# a quadratic tetrahedron's stiffness is poorly conditioned.
FEM_THRESHOLDS = {'InvertedCells': 0, 'MinScaledJacobian': 0.1}
AT_LEAST = {'MinScaledJacobian'}   # figures that pass at or above their threshold (the others at or below)
QUALITY = ('InvertedCells', 'MaxNonOrthogonality', 'MaxSkewness')
FEM_QUALITY = ('InvertedCells', 'MinScaledJacobian')


def _is_deck(dvs):
    """Whether the deformation's input came from a solver's mesh file (not an OpenFOAM case)."""
    return bool(_deformation_source(dvs))


def _fem(dvs):
    """Whether its variants get an FEM solver's verdict (a structural solver's mesh file)."""
    from .meshfile import source_of
    return source_of(dvs._algorithm)[1]


def meshQuality(dvs):
    """The last update's volume-mesh figures as a dict: InvertedCells, MaxNonOrthogonality,
    MaxSkewness (checkMesh's definitions) for a case, InvertedCells and MinScaledJacobian for a
    deck. Raises RuntimeError when MLS Deform reports none."""
    output = dvs._algorithm.GetOutputDataObject(0).GetFieldData()
    figures = {}
    for key in FEM_QUALITY if _fem(dvs) else QUALITY:
        array = output.GetArray(key)
        if array is None:
            problem = output.GetAbstractArray('MeshQualityProblem')
            if not dvs._algorithm.GetMeshQuality():
                raise RuntimeError("MLS Deform's MeshQuality is off, so a variant has no verdict: turn it on "
                                   "(deform.MeshQuality = 1)")
            if problem is not None and problem.GetNumberOfValues():
                raise RuntimeError(f"MLS Deform could not measure the mesh quality: {problem.GetValue(0)}")
            raise RuntimeError(f"MLS Deform reports no {key}: its input has no volume cells (give it the volume mesh, "
                               f"e.g. the OpenFOAM reader's internalMesh, not only the patches)")
        figures[key] = array.GetTuple1(0)
    figures['InvertedCells'] = int(figures['InvertedCells'])
    return figures


def passes(figures, thresholds=None):
    """The verdict: every figure within its threshold (THRESHOLDS, or FEM_THRESHOLDS for a deck's
    figures, with thresholds' entries): at least it for MinScaledJacobian, at most it for the others."""
    defaults = FEM_THRESHOLDS if 'MinScaledJacobian' in figures else THRESHOLDS
    limits = dict(defaults, **(thresholds or {}))
    return all(figures[key] >= limits[key] if key in AT_LEAST else figures[key] <= limits[key] for key in defaults)


def latinHypercube(bounds, samples, seed=0):
    """samples points in the box bounds = [(lower, upper), ...]: each variable's range cut into
    samples equal strata, one point in each (uniform within it), the strata paired at random."""
    if int(samples) != samples or samples < 1:
        raise ValueError(f"samples must be a positive integer, not {samples!r}")
    rng = np.random.default_rng(seed)
    points = np.empty((int(samples), len(bounds)))
    for j, (lower, upper) in enumerate(bounds):
        if lower is None or upper is None:
            raise ValueError("a Latin hypercube needs finite bounds on every variable")
        strata = (rng.permutation(int(samples)) + rng.random(int(samples))) / samples
        points[:, j] = lower + strata * (upper - lower)
    return points


def readTable(path, names, bounds):
    """The rows of a CSV table with one column per design variable (a header of their names, in
    any order; no other column): a list of {name: value}. Raises ValueError naming the row and
    column of a missing, unknown, non-numeric or out-of-bounds entry."""
    with open(path, newline='') as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ValueError(f"{path} is empty: a header row of the variables' names is needed")
    header = [h.strip() for h in rows[0]]
    if sorted(header) != sorted(names):
        raise ValueError(f"{path}: the columns {header} are not the design variables {list(names)}")
    values = []
    for r, row in enumerate(rows[1:], start=2):
        if not any(cell.strip() for cell in row):
            continue
        if len(row) != len(header):
            raise ValueError(f"{path}, row {r}: {len(row)} values for {len(header)} columns")
        entry = {}
        for name, cell in zip(header, row):
            try:
                value = float(cell)
            except ValueError:
                raise ValueError(f"{path}, row {r}, column {name}: {cell!r} is not a number") from None
            lower, upper = bounds[name]
            if not math.isfinite(value) or (lower is not None and value < lower) or (upper is not None and value > upper):
                raise ValueError(f"{path}, row {r}, column {name}: {value} is outside the bounds [{lower}, {upper}]")
            entry[name] = value
        values.append(entry)
    if not values:
        raise ValueError(f"{path} has no rows of values")
    return values


def _deformation(dvs):
    """What the variants are made of besides the variables' values, to tell one design from
    another in a folder: the source case (CasePath), each region's role, point count and centroid
    (which patches it holds), and the set-up's NumberOfSamples, NumberOfIntegrationPoints and
    ReciprocalCondition (the samples, weights and basis). Sums over MPI processes; the centroids
    and the condition to 9 and 6 digits, which round-off of another summation order keeps."""
    from .ranks import all_reduce
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from .deformer import case_path
    field = dvs._algorithm.GetOutputDataObject(0).GetFieldData()
    source = _deformation_source(dvs)
    record = {'deck': source} if source else {'case': case_path(dvs._algorithm.GetInputDataObject(0, 0))}
    for key, digits in (('NumberOfSamples', 12), ('NumberOfIntegrationPoints', 12), ('ReciprocalCondition', 6)):
        array = field.GetArray(key)
        record[key] = float('%.*g' % (digits, array.GetTuple1(0))) if array is not None else None
    regions = []
    for region in dvs._filter.regions():
        points = dvs._filter.output(region).GetPoints()
        xyz = vtk_to_numpy(points.GetData()).astype(np.float64) if points is not None else np.zeros((0, 3))
        count = int(all_reduce(len(xyz), 'sum'))
        total = all_reduce(xyz.sum(axis=0) if len(xyz) else np.zeros(3), 'sum')
        regions.append({'role': int(dvs._filter.role(region)), 'points': count,
                        'centroid': [float('%.9g' % (c / max(count, 1))) for c in total]})
    record['regions'] = regions
    return record


def _deformation_source(dvs):
    from .meshfile import source_of
    return source_of(dvs._algorithm)[0]


def _write_atomically(path, text):
    partial = path + '.writing'
    with open(partial, 'w') as f:
        f.write(text)
    os.replace(partial, path)


def _report_text(names, quality, rows):
    columns = ['variant'] + list(names) + list(quality) + ['ok', 'seconds', 'path']
    lines = [','.join(columns)]
    for row in rows:
        lines.append(','.join(repr(row[c]) if isinstance(row[c], float) else str(row[c]) for c in columns))
    return '\n'.join(lines) + '\n'


def _read_report(path, names, quality):
    if not os.path.exists(path):
        return {}
    kept = {}
    with open(path, newline='') as f:
        for row in csv.DictReader(f):
            entry = {n: float(row[n]) for n in names}
            entry.update({key: float(row[key]) for key in quality})
            entry.update(variant=row['variant'], InvertedCells=int(float(row['InvertedCells'])),
                         ok=row['ok'] == 'True', seconds=float(row['seconds']), path=row['path'])
            kept[entry['variant']] = entry
    return kept


def designOfExperiments(dvs, folder, samples=None, seed=0, table=None, thresholds=None, writeFailed=False, copy=False,
                        verbose=True):
    """Writes the variants of a design (a Latin hypercube of ``samples`` points with ``seed``, or
    the rows of the CSV ``table``) into ``folder`` and returns the report: one dict per variant.
    ``thresholds`` overrides THRESHOLDS' entries (FEM_THRESHOLDS' on a deck); a variant that
    fails them is reported (ok False) and not written unless ``writeFailed``. A case's variant holds
    its own points and links the source's unchanged files (OpenFOAM reads through symbolic links;
    ``copy=True``: self-contained copies); a deck's is always a whole deck (its files copied, the
    nodes' coordinates changed). Prints a progress line per variant (verbose). The design
    variables' values are restored at the end. Raises ValueError for a bad design or table and
    RuntimeError when a deformation or a write fails (what was written stays)."""
    names = dvs.getVarNames()
    if not names:
        raise ValueError("the design has no variables: add some with addHandleDV first")
    bounds = dvs.getBounds()
    if (samples is None) == (table is None):
        raise ValueError("give either samples= (a Latin hypercube) or table= (a CSV file), not both or neither")
    # The pipeline brought up to date first: what tells one design from another (the source, the
    # regions' points, the set-up) and whether the source is a deck exist only once it ran, and a
    # script may call this before any update.
    dvs._updated()
    deck = _is_deck(dvs)
    defaults, quality = (FEM_THRESHOLDS, FEM_QUALITY) if _fem(dvs) else (THRESHOLDS, QUALITY)
    limits = dict(defaults)
    for key, value in (thresholds or {}).items():
        if key not in defaults:
            raise ValueError(f"unknown threshold {key!r} for {'an FEM' if _fem(dvs) else 'a finite-volume'} mesh "
                             f"(known: {', '.join(defaults)})")
        limits[key] = float(value)
    if samples is not None:
        unbounded = [n for n in names if None in tuple(bounds[n])]
        if unbounded:
            raise ValueError(f"design variable{'s' if len(unbounded) > 1 else ''} {', '.join(map(repr, unbounded))} "
                             f"{'have' if len(unbounded) > 1 else 'has'} no lower and upper bound: a Latin hypercube needs both "
                             f"(addHandleDV(..., lower=, upper=); a design file's \"lower\", \"upper\"), or give a table")
        points = latinHypercube([bounds[n] for n in names], samples, seed)
        values = [dict(zip(names, map(float, p))) for p in points]
        origin = {'samples': int(samples), 'seed': seed}
    else:
        values = readTable(table, names, bounds)
        origin = {'table': os.path.abspath(table)}
    folder = os.path.abspath(folder)
    os.makedirs(folder, exist_ok=True)
    design = {'variables': names, 'bounds': [bounds[n] for n in names], 'values': [[v[n] for n in names] for v in values],
              'thresholds': limits, 'writeFailed': bool(writeFailed), 'copy': bool(copy), **origin,
              'deformation': _deformation(dvs)}
    record = os.path.join(folder, 'design.json')
    if os.path.exists(record):
        with open(record) as f:
            earlier = json.load(f)
        if 'deformation' not in earlier:
            raise ValueError(f"{record} is not a design of experiments' record (a design file for mlsdeform-doe.py?): write the "
                             f"variants to another folder, e.g. {os.path.join(folder, 'variants')}")
        differs = sorted(key for key in set(earlier) | set(design) if earlier.get(key) != json.loads(json.dumps(design)).get(key))
        if differs:
            raise ValueError(f"{folder} holds another design (its design.json differs in {', '.join(differs)}): choose "
                             f"another folder or remove it")
    else:
        _write_atomically(record, json.dumps(design, indent=1))
    # variants interrupted while written leave .writing-* folders (a case's) or files (a deck's)
    for entry in os.listdir(folder):
        path = os.path.join(folder, entry)
        if '.writing-' in entry:
            shutil.rmtree(path, ignore_errors=True)
        elif deck and os.path.isdir(path):
            for name in os.listdir(path):
                if '.writing-' in name:
                    os.remove(os.path.join(path, name))
    report_path = os.path.join(folder, 'report.csv')
    width = len(str(len(values) - 1))
    variant_names = ['variant%0*d' % (width, i) for i in range(len(values))]
    kept = _read_report(report_path, names, quality)
    start = dvs.getValues()
    rows, timings = [], []
    try:
        for i, (variant, point) in enumerate(zip(variant_names, values)):
            case = os.path.join(folder, variant, os.path.basename(_deformation_source(dvs)) if deck else 'case.foam')
            done = kept.get(variant)
            if done is not None and (not done['path'] or os.path.exists(done['path'])):
                rows.append(done)  # complete: written, or reported and not written (it failed the thresholds)
                continue
            began = time.perf_counter()
            dvs.setDesignVars(point)
            dvs._updated()   # the deformation and its verdict; not update()'s copy of the points (28.5 MB on 1M)
            figures = meshQuality(dvs)
            ok = passes(figures, limits)
            path = ''
            if ok or writeFailed:
                dvs._filter.save(case, overwrite=True, link=not copy)
                path = case
            seconds = time.perf_counter() - began
            row = dict(point, **figures, variant=variant, ok=ok, seconds=seconds, path=path)
            rows.append(row)
            _write_atomically(report_path, _report_text(names, quality, rows))
            timings.append(seconds)
            if verbose:
                remaining = (len(values) - i - 1) * float(np.mean(timings))
                print('%s (%d of %d): %s, %.2f s (mean %.2f s), about %.0f s left' % (
                    variant, i + 1, len(values), 'ok' if ok else 'FAILS the thresholds' + ('' if writeFailed else ', not written'),
                    seconds, float(np.mean(timings)), remaining), flush=True)
    finally:
        dvs.setDesignVars(start)
    _write_atomically(report_path, _report_text(names, quality, rows))
    return rows
