"""What the constraint examples share (coplanar_feet.py, symmetric_variant.py,
wheelbase_distance.py, wall_thickness_offset.py): the plugin loaded from the command line, box
regions, a deformation's rest positions and displacements, and the comparison of a measure
without and with the constraint that prints, writes the constrained variant and gives the exit
code.

    pvbatch EXAMPLE.py PLUGIN OUTPUT_DIR
"""
import os
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin, SaveData
from vtk.util.numpy_support import vtk_to_numpy

plugin, out_dir = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())  # ConstraintRegion, MLSDeform, ... of this module
os.makedirs(out_dir, exist_ok=True)


def box(model, role, lower, upper, **properties):
    """A Constraint Region of the model's points in the box [lower, upper]."""
    region = ConstraintRegion(Input=model, Role=role, **properties)  # noqa: F821 (from the plugin)
    region.Region = 'Box'
    region.Region.Position = lower
    region.Region.Length = [u - l for u, l in zip(upper, lower)]
    return region


def rest_and_displacement(deformed):
    """The deformation's rest positions (its input's points) and displacements (in double
    precision: the output's points are rounded to the input's float precision), numpy, one row
    per point; raises RuntimeError with the filter's message when it failed."""
    data = servermanager.Fetch(deformed)
    error = data.GetFieldData().GetAbstractArray('DeformationError')
    if error is not None:
        raise RuntimeError(error.GetValue(0))
    rest = vtk_to_numpy(servermanager.Fetch(deformed.Input).GetPoints().GetData()).astype(float)
    return rest, vtk_to_numpy(data.GetPointData().GetArray('Displacement'))


def report(what, before, after, kept, name, holds):
    """Prints the measure without and with the constraint, writes the constrained variant to
    OUTPUT_DIR/name.vtp and exits with 0 when holds(after), else 1."""
    print('%s: %.6g without the constraint, %.6g with it' % (what, before, after))
    result = os.path.join(out_dir, name + '.vtp')
    SaveData(result, proxy=kept)
    print('wrote', result)
    sys.exit(0 if holds(after) else 1)
