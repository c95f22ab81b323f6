"""Issue 14: MLS Deform split over MPI ranks gives the serial deformation.

  pvbatch test_distributed.py PLUGIN WORK reference
      writes WORK/scene.vtm (a polydata body inside a tetrahedral box, one block each) and, on one
      process, the deformed positions of every point (WORK/reference.npz);
  mpiexec -n N pvbatch test_distributed.py PLUGIN WORK compare
      reads the scene in parallel (the XML reader hands out blocks), redistributes it over the N
      ranks (RedistributeDataSet), deforms it and checks every point against the reference;
  pvpython test_distributed.py PLUGIN WORK server HOST:PORT
      the same, connected to a pvserver (e.g. mpiexec -n 2 pvserver --server-port=PORT).

The regions: a Handle (the body, moved and turned), the box's sides Fixed, its floor Slip, a
Planarity patch, a Rigid block of tetrahedra (one constraint set per cell), two Distance patches
and an Offset patch with a plane as its reference surface, so that the gathering of positions,
constraint sets, slip planes and reference triangles is exercised. Then NaN coordinates in some
pieces: every rank reports the error (none waits for another forever).
"""
import os
import sys

import numpy as np
import paraview.simple as pvs
from paraview import servermanager
from paraview.simple import LoadPlugin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sphere_in_box  # noqa: E402
from vtk.numpy_interface import dataset_adapter as dsa

plugin, work, mode = sys.argv[1:4]
if mode == 'server':
    # pvpython connected to pvserver running on MPI ranks (HOST:PORT): the plugin on both sides
    host, port = sys.argv[4].split(':')
    pvs.Connect(host, int(port))
    LoadPlugin(plugin, remote=True, ns=globals())
LoadPlugin(plugin, remote=False, ns=globals())
failures = []


def check(condition, what):
    print(('ok   ' if condition else 'FAIL ') + what, flush=True)
    if not condition:
        failures.append(what)


def box_region(source, role, bounds, **properties):
    return sphere_in_box.box_region(ConstraintRegion, source, role, bounds, **properties)  # noqa: F821



def deformed(source):
    """The MLS Deform of source with the regions above, and its field data and points gathered
    on the first rank: rest position (the input's, a point array) and deformed position."""
    rest = pvs.Calculator(Input=source, AttributeType='Point Data', ResultArrayName='Rest', Function='coords',
                          ResultArrayType='Double')
    handle = box_region(rest, 'Handle', [-0.35, 0.35] * 3, Translation=[0.05, 0.1, 0.15], Rotation=[0, 0, 10])
    fixed = ConstraintRegion(Input=rest, Role='Fixed', InsideOut=1)
    fixed.Region = 'Box'
    fixed.Region.UseReferenceBounds = 0
    fixed.Region.Position = [-0.99, -0.99, -1.01]
    fixed.Region.Length = [1.98, 1.98, 2.0]
    slip = box_region(rest, 'Slip', [-0.99, 0.99, -0.99, 0.99, -1.01, -0.99])
    planar = box_region(rest, 'Planarity', [0.45, 0.8, -0.5, 0.5, 0.3, 0.34])
    rigid = box_region(rest, 'Rigid', [-0.8, -0.5, -0.3, 0.3, -0.3, 0.3], CellSets=1)
    # a wheelbase below the body and a wall thickness above it: their groups' positions and the
    # reference surface's triangles gathered over the ranks
    axles = [box_region(rest, 'Distance', [x0, x0 + 0.25, -0.3, 0.3, -0.7, -0.5], DistanceAxis=[1, 0, 0]) for x0 in (-0.7, 0.45)]
    wall = box_region(rest, 'Offset', [-0.3, 0.3, -0.3, 0.3, 0.45, 0.6], MinimumDistance=0.38)
    wall.Surface = pvs.Plane(Origin=[-1, -1, 0.95], Point1=[1, -1, 0.95], Point2=[-1, 1, 0.95], XResolution=4, YResolution=4)
    deform = MLSDeform(Input=rest, Regions=[handle, fixed, slip, planar, rigid] + axles + [wall], NumberOfSamples=400)
    return gathered(deform)


def gathered(proxy):
    """The proxy's output gathered on the client: rest positions, deformed positions (rest +
    Displacement), the numeric field data and the DeformationError message (None without)."""
    data = servermanager.Fetch(proxy)
    out = dsa.WrapDataObject(data)
    fields = data.GetFieldData()
    field = {}
    for a in range(fields.GetNumberOfArrays()):
        array = fields.GetArray(a)  # None for string arrays
        if array is not None:
            field[array.GetName()] = np.array([array.GetTuple1(t) for t in range(array.GetNumberOfTuples())])
    error = fields.GetAbstractArray('DeformationError')
    keys, moved = [], []
    for block in out:
        if block.VTKObject.GetPointData().GetArray('Displacement') is not None:
            field['Displacement'] = True
        if block.GetNumberOfPoints() == 0:
            continue
        keys.append(np.asarray(block.PointData['Rest']))
        # in double precision: the output's points have the precision of the input's, and
        # RedistributeDataSet makes float points double
        # (without Displacement, after an error: the points)
        moved.append(keys[-1] + np.asarray(block.PointData['Displacement']) if 'Displacement' in field
                     else np.asarray(block.Points, dtype=float))
    return (np.concatenate(keys), np.concatenate(moved), field,
            error.GetValue(0) if error is not None else None)


if mode == 'reference':
    os.makedirs(work, exist_ok=True)
    scene = os.path.join(work, 'scene.vtm')
    sphere_in_box.write_scene(scene, 12)
    rest, moved, field, error = deformed(pvs.OpenDataFile(scene))
    check(error is None, 'the serial deformation succeeds (%s)' % error)
    field.pop('Displacement')
    np.savez(os.path.join(work, 'reference.npz'), rest=rest, moved=moved, **field)
    check(np.abs(moved - rest).max() > 0.05, 'the handle moves the scene')
else:
    ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
    reference = np.load(os.path.join(work, 'reference.npz'))
    source = pvs.RedistributeDataSet(Input=pvs.OpenDataFile(os.path.join(work, 'scene.vtm')))
    rest, moved, field, error = deformed(source)
    check(error is None, 'the deformation on %d ranks succeeds (%s)' % (ranks, error))
    np.savez(os.path.join(work, 'ranks%d.npz' % ranks), rest=rest, moved=moved)  # for a look after a failure
    # every point matched to the reference by its rest position (exact: the same doubles)
    index = {tuple(x): i for i, x in enumerate(reference['rest'])}
    which = np.array([index.get(tuple(x), -1) for x in rest])
    check((which >= 0).all(), 'every point of the %d pieces is a point of the scene' % ranks)
    check(len(set(which)) == len(reference['rest']), 'every point of the scene is in a piece (%d of %d)' % (len(set(which)), len(reference['rest'])))
    diagonal = np.linalg.norm(reference['rest'].max(axis=0) - reference['rest'].min(axis=0))
    # the bound of issue 14: the serial position within 1e-10 of the diagonal
    deviation = np.linalg.norm(moved - reference['moved'][which], axis=1).max() / diagonal
    check(deviation <= 1e-10, 'every point within 1e-10 of the diagonal of its serial position (%.3g)' % deviation)
    # a point held by two pieces moves identically in both
    order = np.lexsort(rest.T)
    same = (np.diff(rest[order], axis=0) == 0).all(axis=1)
    shared = np.abs(np.diff(moved[order], axis=0)[same]).max() if same.any() else 0.0
    check(shared == 0, 'points shared by pieces are identical (%d shared, largest difference %g)' % (same.sum(), shared))
    # the global figures of the field data: the same as the serial ones; the mesh quality's too
    # (the faces between the pieces measured across them) on the points, which are within 1e-10
    # of the diagonal of the serial ones: on cells 1e-3 of the diagonal a face's measures move by
    # 1e-7 relative (1e-6 allowed); at rest they are the serial ones
    for name in ('NumberOfSamples', 'NumberOfIntegrationPoints', 'HandleResidual', 'FixedResidual', 'ConstraintResidual',
                 'ConstraintPoints', 'ConstraintSets', 'InvertedCells', 'MaxNonOrthogonality', 'MaxSkewness',
                 'OriginalMaxNonOrthogonality', 'OriginalMaxSkewness'):
        rtol = 1e-6 if name in ('MaxNonOrthogonality', 'MaxSkewness') else 1e-9
        ok = name in field and name in reference and np.allclose(field[name], reference[name], rtol=rtol, atol=1e-14)
        check(ok, '%s is the serial one (%s, serial %s)' % (name, field.get(name), reference[name] if name in reference else None))
    print('%d ranks: %d points in the pieces, %d in the scene' % (ranks, len(rest), len(reference['rest'])))
    if mode == 'server':
        # saved by the server's ranks and read back: the same deformation
        saved = os.path.join(work, 'server-variant.vtm')
        pvs.SaveData(saved, proxy=pvs.GetActiveSource())
        rest, moved, _, _ = gathered(pvs.OpenDataFile(saved))
        which = np.array([index.get(tuple(x), -1) for x in rest])
        check((which >= 0).all() and np.linalg.norm(moved - reference['moved'][which], axis=1).max() <= 1e-10 * diagonal,
              'the variant saved by the server (SaveData) holds the serial deformation')
    # bad input on some ranks only (NaN coordinates where x > 0.95): every rank stops with the
    # message instead of waiting for the others, and the output is the unchanged input
    bad = pvs.Calculator(Input=source, CoordinateResults=1, ReplaceInvalidResults=0,
                         Function='coords+ln(0.95-coordsX)*iHat')  # NaN where x > 0.95
    rest, moved, field, error = deformed(bad)
    check(error is not None and 'NaN' in error, 'NaN coordinates in a piece stop every rank with a clear message (%s)' % error)
    check('Displacement' not in field, 'the output is the unchanged input (no Displacement)')

if failures:
    print('%d check(s) failed' % len(failures))
    sys.exit(1)
