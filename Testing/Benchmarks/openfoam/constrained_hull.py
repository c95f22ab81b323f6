"""Exact constraints against the soft ones (issue 31, point 7) on the hull case: the hull's
largest planar and largest cylindrical primitive (vtkPrimitiveDetector on the hull patch) that lie
wholly behind the bow kept while the bow (the hull's points ahead of 85% of its length) moves; the inlet and outlet fixed,
the sides, bottom and top slipping. Per method (soft, exact): the set-up (the first deformation:
sampling, operators, factorization, the blend and the constraint iteration), the median time of
a variation (a new bow motion) and the largest residual of the kept primitives (of the bounding-box diagonal) and
inverted cells over the variations. One JSON line per method, then the ratios exact / soft;
exits with 1 when the exact residual exceeds 1e-9 or a variant has an inverted cell.

    python3 constrained_hull.py PLUGIN_DIR CASE.foam [VARIATIONS]
"""
import json
import os
import statistics
import sys
import time

plugin_dir, foam = sys.argv[1:3]
variations = int(sys.argv[3]) if len(sys.argv) > 3 else 5
sys.path.insert(0, plugin_dir)
from mlsdeform import vtkfoam  # noqa: E402
from mlsdeform.deformer import _load_wrapping  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkBox, vtkMultiBlockDataSet  # noqa: E402

w = _load_wrapping()
Region = w.vtkConstraintRegion
fixed, slip = ['inlet', 'outlet'], ['sideYmin', 'sideYmax', 'bottom', 'top']
reader = vtkfoam.open_case(foam, ['hull'] + fixed + slip, decompose_polyhedra=False)
boundary = reader.GetOutput().GetBlock(1)
patches = {boundary.GetMetaData(i).Get(vtkMultiBlockDataSet.NAME()): boundary.GetBlock(i) for i in range(boundary.GetNumberOfBlocks())}
hull = patches['hull']
x0, x1 = hull.GetBounds()[0:2]

# the largest plane and the largest cylinder of the hull patch
detector = w.vtkPrimitiveDetector()
detector.SetInputData(hull)
detector.SetDetectSpheres(0)
detector.SetDetectCones(0)
detector.Update()
table = detector.GetOutputDataObject(1)
columns = {table.GetColumnName(c): c for c in range(table.GetNumberOfColumns())}
rows = [(table.GetValue(r, columns['Type']).ToString(), table.GetValue(r, columns['Id']).ToInt(),
         table.GetValue(r, columns['Faces']).ToInt()) for r in range(table.GetNumberOfRows())]
bow_start = x0 + 0.85 * (x1 - x0)
kept = []  # (kind, row, region): of each kind the largest primitive wholly behind the bow
for kind in ('Plane', 'Cylinder'):
    for row in sorted((r for r in rows if r[0] == kind), key=lambda r: -r[2]):
        region = Region()
        region.SetInputConnection(detector.GetOutputPort(0))
        region.SetSelectionMode(Region.Primitive)
        region.SetRole(Region.FromPrimitive)
        region.SetPrimitiveId(row[1])
        region.Update()
        if region.GetOutput().GetBounds()[1] < bow_start:
            kept.append((kind, row, region))
            break

bow = Region()
bow.SetInputData(hull)
bow.SetRole(Region.Handle)
box = vtkBox()
box.SetBounds(bow_start, x1 + 1, -10, 10, -10, 10)
bow.SetRegion(box)
others = [vtkfoam.patch_region(reader, p, Region.Fixed) for p in fixed] + [vtkfoam.patch_region(reader, p, Region.Slip) for p in slip]


def motion(v):
    """The bow's v-th motion: forwards and up by a few millimetres (the hull is 6.3 m long)."""
    return (0.01 * (1 + 0.1 * v), 0, 0.005 * (1 + 0.05 * v))


# a first deformation loads what every later one shares (libraries, the reader's arrays): not counted
warm_up = w.vtkMLSDeformFilter()
warm_up.SetInputData(0, reader.GetOutput())
for region in [bow] + others:
    warm_up.AddInputConnection(1, region.GetOutputPort())
warm_up.Update()
del warm_up

figures = {}
for method, exact in (('soft', 0), ('exact', 1)):
    deform = w.vtkMLSDeformFilter()
    deform.SetInputData(0, reader.GetOutput())
    for region in [bow] + others + [r for _, _, r in kept]:
        deform.AddInputConnection(1, region.GetOutputPort())
    deform.SetExactConstraints(exact)
    deform.SetMeshQuality(1)
    bow.SetTranslation(*motion(0))
    start = time.perf_counter()
    deform.Update()
    setup = time.perf_counter() - start
    times, residual, inverted = [], 0.0, 0
    for v in range(1, variations + 1):
        bow.SetTranslation(*motion(v))
        start = time.perf_counter()
        deform.Update()
        times.append(time.perf_counter() - start)
        field = deform.GetOutputDataObject(0).GetFieldData()
        if field.GetAbstractArray('DeformationError') is not None:
            sys.exit('MLS Deform failed: %s' % field.GetAbstractArray('DeformationError').GetValue(0))
        # the kept primitives' residuals: the last of the constraint regions (the slip planes' come
        # before the slide that puts their points on their planes)
        residuals = field.GetArray('ConstraintResidual')
        n = residuals.GetNumberOfTuples()
        residual = max([residual] + [residuals.GetValue(k) for k in range(n - len(kept), n)])
        inverted = max(inverted, int(field.GetArray('InvertedCells').GetValue(0)))
    figures[method] = {'scene': 'hull case, bow moved, largest plane (%d faces) and cylinder (%d faces) of the hull kept'
                       % (kept[0][1][2], kept[1][1][2]), 'method': method,
                       'points': reader.GetOutput().GetBlock(0).GetNumberOfPoints(),
                       'cells': reader.GetOutput().GetBlock(0).GetNumberOfCells(),
                       'threads': int(os.environ.get('OMP_NUM_THREADS', '0')), 'setup_s': round(setup, 2),
                       'variation_median_s': round(statistics.median(times), 3), 'largest_constraint_residual': residual,
                       'inverted_cells': inverted}
    print(json.dumps(figures[method]), flush=True)
print(json.dumps({'exact/soft setup': round(figures['exact']['setup_s'] / figures['soft']['setup_s'], 2),
                  'exact/soft variation': round(figures['exact']['variation_median_s'] / figures['soft']['variation_median_s'], 2)}))
sys.exit(0 if figures['exact']['largest_constraint_residual'] <= 1e-9 and figures['exact']['inverted_cells'] == 0 else 1)
