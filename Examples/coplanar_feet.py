"""Two feet kept on one plane (issue 31's Coplanar constraint): a plate, its left end fixed, its
middle lifted and twisted. Without constraints its right end rises with the middle; with the
two ends as Coplanar regions (one group) the right end stays in the left end's plane, to
round-off (exact constraints). Prints how far the right end leaves that plane in both and writes
the constrained variant; exits with 1 if the ends are not coplanar within 1e-9 of the diagonal.

    pvbatch coplanar_feet.py PLUGIN OUTPUT_DIR
"""
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import LoadPlugin, Plane, SaveData
from vtk.util.numpy_support import vtk_to_numpy

plugin, out_dir = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
os.makedirs(out_dir, exist_ok=True)

plate = Plane(Origin=[0, 0, 0], Point1=[2, 0, 0], Point2=[0, 1, 0], XResolution=40, YResolution=20)


def box(role, lower, upper, **properties):
    region = ConstraintRegion(Input=plate, Role=role, **properties)  # noqa: F821 (from the plugin)
    region.Region = 'Box'
    region.Region.Position = lower
    region.Region.Length = [u - l for u, l in zip(upper, lower)]
    return region


fixed = box('Fixed', [-0.01, -0.01, -0.01], [0.21, 1.01, 0.01])
middle = box('Handle', [0.8, -0.01, -0.01], [1.2, 1.01, 0.01], Translation=[0, 0, 0.2], Rotation=[10, 0, 0])
left_foot = box('Coplanar', [-0.01, -0.01, -0.01], [0.31, 1.01, 0.01], CoplanarGroup=0)
right_foot = box('Coplanar', [1.69, -0.01, -0.01], [2.01, 1.01, 0.01], CoplanarGroup=0)


def off_plane(deformed):
    """The largest distance of the two feet's points from the least-squares plane of both."""
    data = servermanager.Fetch(deformed)
    error = data.GetFieldData().GetAbstractArray('DeformationError')
    if error is not None:
        raise RuntimeError(error.GetValue(0))
    d = vtk_to_numpy(data.GetPointData().GetArray('Displacement'))
    x = vtk_to_numpy(data.GetPoints().GetData()) - d
    feet = (x[:, 0] <= 0.3) | (x[:, 0] >= 1.7)
    y = x[feet] + d[feet]
    centred = y - y.mean(axis=0)
    normal = np.linalg.svd(centred)[2][2]
    return np.abs(centred @ normal).max()


diagonal = np.sqrt(5.0)
free = MLSDeform(Input=plate, Regions=[fixed, middle])  # noqa: F821
kept = MLSDeform(Input=plate, Regions=[fixed, middle, left_foot, right_foot])  # noqa: F821
before, after = off_plane(free), off_plane(kept)
print('the feet off their common plane: %.3g without the Coplanar regions, %.3g with them (of the diagonal)'
      % (before / diagonal, after / diagonal))
result = os.path.join(out_dir, 'coplanar_feet.vtp')
SaveData(result, proxy=kept)
print('wrote', result)
sys.exit(0 if after <= 1e-9 * diagonal else 1)
