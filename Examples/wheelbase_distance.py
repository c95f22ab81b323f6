"""A wheelbase kept (issue 31's Distance constraint): a floor plate, its rear end fixed, its front
end pulled forwards and up. Without constraints the front axle's mounting patch follows and the
wheelbase grows; with the two axles' patches as Distance regions of one group, measured along x,
the wheelbase stays as it was to round-off (exact constraints) while the plate stretches
between them and in front. Prints the change of the wheelbase in both and writes the
constrained variant; exits with 1 if it changed by more than 1e-9 of the diagonal.

    pvbatch wheelbase_distance.py PLUGIN OUTPUT_DIR
"""
import os
import sys

import numpy as np
from paraview.simple import Plane

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from constraint_scene import MLSDeform, box, report, rest_and_displacement  # noqa: E402

floor = Plane(Origin=[0, 0, 0], Point1=[4, 0, 0], Point2=[0, 1.6, 0], XResolution=60, YResolution=24)
rear = box(floor, 'Fixed', [-0.01, -0.01, -0.01], [0.21, 1.61, 0.01])
front = box(floor, 'Handle', [3.79, -0.01, -0.01], [4.01, 1.61, 0.01], Translation=[0.3, 0, 0.1])
axles = [[0.62, 1.02], [2.9, 3.3]]  # the x ranges of the rear and front axles' mounting patches (between grid lines)
mounts = [box(floor, 'Distance', [x0, -0.01, -0.01], [x1, 1.61, 0.01], ConstraintGroup=0, DistanceAxis=[1, 0, 0])
          for x0, x1 in axles]


def wheelbase_change(deformed):
    """How much the distance along x of the two patches' centroids changed, over the diagonal."""
    x, d = rest_and_displacement(deformed)
    change = 0
    for sign, (x0, x1) in zip([-1, 1], axles):
        patch = (x[:, 0] >= x0) & (x[:, 0] <= x1)
        change += sign * d[patch, 0].mean()
    return abs(change) / np.hypot(4, 1.6)


kept = MLSDeform(Input=floor, Regions=[rear, front] + mounts)
report('change of the wheelbase, of the diagonal', wheelbase_change(MLSDeform(Input=floor, Regions=[rear, front])),
       wheelbase_change(kept), kept, 'wheelbase_distance', lambda after: after <= 1e-9)
