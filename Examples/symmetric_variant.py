"""A symmetric variant from an asymmetric handle motion (issue 31's Symmetric constraint): a
sphere, its bottom fixed, a patch on one side pushed outwards and up. Without a Symmetric region
only that side moves; with one (all points, mirror plane y = 0) the other side moves the mirrored
way and the variant is mirror-symmetric to round-off. Prints the largest asymmetry of both and
writes the symmetric variant; exits with 1 if it is not symmetric within 1e-9 of the diagonal.

    pvbatch symmetric_variant.py PLUGIN OUTPUT_DIR
"""
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import LoadPlugin, SaveData, Sphere
from vtk.util.numpy_support import vtk_to_numpy

plugin, out_dir = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
os.makedirs(out_dir, exist_ok=True)

body = Sphere(Radius=1.0, ThetaResolution=32, PhiResolution=24)


def box(role, lower, upper, **properties):
    region = ConstraintRegion(Input=body, Role=role, **properties)  # noqa: F821 (from the plugin)
    region.Region = 'Box'
    region.Region.Position = lower
    region.Region.Length = [u - l for u, l in zip(upper, lower)]
    return region


fixed = box('Fixed', [-2, -2, -2], [2, 2, -0.7])
patch = box('Handle', [-0.5, -2, 0.0], [0.5, -0.6, 0.8], Translation=[0.05, -0.15, 0.1])
mirror = ConstraintRegion(Input=body, Role='Symmetric', SelectionMode='AllPoints',  # noqa: F821
                          SymmetryOrigin=[0, 0, 0], SymmetryNormal=[0, 1, 0])


def asymmetry(deformed):
    """The largest |d_i - R d_j| over the points and their mirror images (y -> -y)."""
    data = servermanager.Fetch(deformed)
    error = data.GetFieldData().GetAbstractArray('DeformationError')
    if error is not None:
        raise RuntimeError(error.GetValue(0))
    x = vtk_to_numpy(data.GetPoints().GetData()) - vtk_to_numpy(data.GetPointData().GetArray('Displacement'))
    d = vtk_to_numpy(data.GetPointData().GetArray('Displacement'))
    image = x * [1, -1, 1]
    partner = np.array([np.argmin(np.linalg.norm(x - p, axis=1)) for p in image])
    return np.abs(d - d[partner] * [1, -1, 1]).max()


diagonal = 2 * np.sqrt(3)
one_sided = MLSDeform(Input=body, Regions=[fixed, patch])  # noqa: F821
symmetric = MLSDeform(Input=body, Regions=[fixed, patch, mirror])  # noqa: F821
before, after = asymmetry(one_sided), asymmetry(symmetric)
print('largest asymmetry of the displacement: %.3g without the Symmetric region, %.3g with it (of the diagonal)'
      % (before / diagonal, after / diagonal))
result = os.path.join(out_dir, 'symmetric_variant.vtp')
SaveData(result, proxy=symmetric)
print('wrote', result)
sys.exit(0 if after <= 1e-9 * diagonal else 1)
