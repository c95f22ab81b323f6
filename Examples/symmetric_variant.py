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
from paraview.simple import Sphere

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from constraint_scene import ConstraintRegion, MLSDeform, box, report, rest_and_displacement  # noqa: E402

body = Sphere(Radius=1.0, ThetaResolution=32, PhiResolution=24)
fixed = box(body, 'Fixed', [-2, -2, -2], [2, 2, -0.7])
patch = box(body, 'Handle', [-0.5, -2, 0.0], [0.5, -0.6, 0.8], Translation=[0.05, -0.15, 0.1])
mirror = ConstraintRegion(Input=body, Role='Symmetric', SelectionMode='AllPoints',
                          SymmetryOrigin=[0, 0, 0], SymmetryNormal=[0, 1, 0])


def asymmetry(deformed):
    """The largest |d_i - R d_j| over the points and their mirror images (y -> -y), over the
    diagonal."""
    x, d = rest_and_displacement(deformed)
    image = x * [1, -1, 1]
    partner = np.array([np.argmin(np.linalg.norm(x - p, axis=1)) for p in image])
    return np.abs(d - d[partner] * [1, -1, 1]).max() / (2 * np.sqrt(3))


symmetric = MLSDeform(Input=body, Regions=[fixed, patch, mirror])
report('largest asymmetry of the displacement, of the diagonal', asymmetry(MLSDeform(Input=body, Regions=[fixed, patch])),
       asymmetry(symmetric), symmetric, 'symmetric_variant', lambda after: after <= 1e-9)
