"""A minimum wall thickness kept (issue 31's Offset constraint): an outer skin (a sphere of radius
1, its bottom fixed) around an inner part (a sphere of radius 0.75 that does not move), a patch
of the skin dented inwards by 0.14. Without constraints the skin around the dent comes nearer
than 0.2 to the inner part; with the skin as an Offset region (the inner part its Surface input,
Minimum Distance 0.2) it stays at 0.2 or more everywhere outside the dent. Prints the least
distance of the skin around the dent from the inner part in both and writes the constrained
variant; exits with 1 if it is less than 0.2 by more than 1e-9 of the diagonal.

    pvbatch wall_thickness_offset.py PLUGIN OUTPUT_DIR
"""
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import Sphere
from vtkmodules.vtkFiltersCore import vtkImplicitPolyDataDistance

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from constraint_scene import MLSDeform, box, report, rest_and_displacement  # noqa: E402

THICKNESS = 0.2
skin = Sphere(Radius=1.0, ThetaResolution=48, PhiResolution=32)
inner = Sphere(Radius=0.75, ThetaResolution=32, PhiResolution=24)
fixed = box(skin, 'Fixed', [-2, -2, -2], [2, 2, -0.8])
dent = box(skin, 'Handle', [0.9, -0.3, -0.3], [1.1, 0.3, 0.3], Translation=[-0.14, 0, 0])
outside_dent = [[-2, -2, -0.79], [0.89, 2, 2]]  # the skin beside the dent, up to the fixed bottom
wall = box(skin, 'Offset', *outside_dent, MinimumDistance=THICKNESS)
wall.Surface = inner

distance = vtkImplicitPolyDataDistance()  # from the inner part's triangles, as the constraint measures
distance.SetInput(servermanager.Fetch(inner))


def least_thickness(deformed):
    """The least distance of the skin beside the dent from the inner part."""
    x, d = rest_and_displacement(deformed)
    lower, upper = np.array(outside_dent)
    beside = np.all((x >= lower) & (x <= upper), axis=1)
    return min(abs(distance.EvaluateFunction(*p)) for p in x[beside] + d[beside])


kept = MLSDeform(Input=skin, Regions=[fixed, dent, wall])
report('least wall thickness beside the dent', least_thickness(MLSDeform(Input=skin, Regions=[fixed, dent])),
       least_thickness(kept), kept, 'wall_thickness_offset', lambda after: after >= THICKNESS - 1e-9 * 2 * np.sqrt(3))
