"""Two feet kept on one plane (issue 31's Coplanar constraint): a plate, its left end fixed, its
middle lifted and twisted. Without constraints its right end rises with the middle; with the
two ends as Coplanar regions (one group) the right end stays in the left end's plane, to
round-off (exact constraints). Prints how far the feet leave their common plane in both and
writes the constrained variant; exits with 1 if the ends are not coplanar within 1e-9 of the
diagonal.

    pvbatch coplanar_feet.py PLUGIN OUTPUT_DIR
"""
import os
import sys

import numpy as np
from paraview.simple import Plane

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from constraint_scene import MLSDeform, box, report, rest_and_displacement  # noqa: E402

plate = Plane(Origin=[0, 0, 0], Point1=[2, 0, 0], Point2=[0, 1, 0], XResolution=40, YResolution=20)
fixed = box(plate, 'Fixed', [-0.01, -0.01, -0.01], [0.21, 1.01, 0.01])
middle = box(plate, 'Handle', [0.8, -0.01, -0.01], [1.2, 1.01, 0.01], Translation=[0, 0, 0.2], Rotation=[10, 0, 0])
left_foot = box(plate, 'Coplanar', [-0.01, -0.01, -0.01], [0.31, 1.01, 0.01], ConstraintGroup=0)
right_foot = box(plate, 'Coplanar', [1.69, -0.01, -0.01], [2.01, 1.01, 0.01], ConstraintGroup=0)


def off_plane(deformed):
    """The largest distance of the two feet's points from the least-squares plane of both, over
    the diagonal."""
    x, d = rest_and_displacement(deformed)
    feet = (x[:, 0] <= 0.3) | (x[:, 0] >= 1.7)
    y = x[feet] + d[feet]
    centred = y - y.mean(axis=0)
    normal = np.linalg.svd(centred)[2][2]
    return np.abs(centred @ normal).max() / np.sqrt(5.0)


kept = MLSDeform(Input=plate, Regions=[fixed, middle, left_foot, right_foot])
report('the feet off their common plane, of the diagonal', off_plane(MLSDeform(Input=plate, Regions=[fixed, middle])),
       off_plane(kept), kept, 'coplanar_feet', lambda after: after <= 1e-9)
