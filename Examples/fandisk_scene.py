"""The fandisk scene of the example scripts (paper Fig. 8) and their side-by-side pictures.
After open_fandisk() the plugin's proxies are attributes of this module (scene.MLSDeform)."""
import os
import sys

from paraview.simple import (ColorBy, CreateLayout, CreateView, GetColorTransferFunction,
                             GetScalarBar, LoadPlugin, OpenDataFile, SaveScreenshot, Show)


def load_plugin(plugin):
    """Loads the plugin; its proxies become attributes of this module (scene.MLSDeform)."""
    LoadPlugin(plugin, remote=False, ns=globals())


def open_fandisk():
    """From the command line PLUGIN FANDISK.off OUTPUT_DIR: loads the plugin, opens the part and
    creates the output folder. Returns the part, its bounds and the folder."""
    plugin, mesh, out_dir = sys.argv[1:4]
    load_plugin(plugin)
    os.makedirs(out_dir, exist_ok=True)
    part = OpenDataFile(mesh)
    part.UpdatePipeline()
    return part, part.GetDataInformation().GetBounds(), out_dir


def box_region(source, role, lower, upper, **properties):
    """A Constraint Region of the given role: the points of source inside the box lower-upper."""
    region = ConstraintRegion(Input=source, Role=role, **properties)  # noqa: F821 (from the plugin)
    region.Region = 'Box'
    region.Region.Position = list(lower)
    region.Region.Length = [u - l for u, l in zip(upper, lower)]
    return region


def fixed_and_handle(part, bounds):
    """Fixed: the bottom 10% of the part. Handle: the top 25%, moved along -x by 15% of the height."""
    xmin, xmax, ymin, ymax, zmin, zmax = bounds
    height = zmax - zmin
    margin = 0.01 * height
    lower, upper = [xmin - margin, ymin - margin], [xmax + margin, ymax + margin]
    fixed = box_region(part, 'Fixed', lower + [zmin - margin], upper + [zmin + 0.1 * height])
    handle = box_region(part, 'Handle', lower + [zmax - 0.25 * height], upper + [zmax + margin],
                        Translation=[-0.15 * height, 0.0, 0.0])
    return fixed, handle


# Feature lines: the sharp edges (feature angle 30 degrees), split into lines at their junctions
# (a point array LineId, -1 at junctions).
SPLIT_LINES = """
import numpy as np
from vtk.util.numpy_support import numpy_to_vtk
edges = self.GetInputDataObject(0, 0)
n = edges.GetNumberOfPoints()
neighbours = [[] for _ in range(n)]
for c in range(edges.GetNumberOfCells()):
    ids = edges.GetCell(c).GetPointIds()
    for j in range(ids.GetNumberOfIds() - 1):
        a, b = ids.GetId(j), ids.GetId(j + 1)
        neighbours[a].append(b)
        neighbours[b].append(a)
line = -np.ones(n)
count = 0
for start in range(n):
    if line[start] >= 0 or len(neighbours[start]) != 2:
        continue
    stack = [start]
    line[start] = count
    while stack:
        for q in neighbours[stack.pop()]:
            if line[q] < 0 and len(neighbours[q]) == 2:
                line[q] = count
                stack.append(q)
    count += 1
output = self.GetOutputDataObject(0)
output.ShallowCopy(edges)
array = numpy_to_vtk(line, deep=1)
array.SetName('LineId')
output.GetPointData().AddArray(array)
"""


def fig8_constraints(part, bounds):
    """Paper Fig. 8's constraints: FeatureLine regions on every sharp feature line (8 points or
    more) that lies in the band that bends, and a Planarity region on the upper half of the planar
    face at x = xmin. Returns the planar region and the list of feature-line regions."""
    from paraview import servermanager
    from paraview.simple import FeatureEdges, ProgrammableFilter
    xmin, xmax, ymin, ymax, zmin, zmax = bounds
    height = zmax - zmin
    margin = 0.01 * height
    edges = ProgrammableFilter(Input=FeatureEdges(Input=part, BoundaryEdges=0, FeatureEdges=1, NonManifoldEdges=0,
                                                  ManifoldEdges=0, FeatureAngle=30), Script=SPLIT_LINES)
    lines = servermanager.Fetch(edges)
    line_id = lines.GetPointData().GetArray('LineId')
    z_of = {}
    for i in range(lines.GetNumberOfPoints()):
        z_of.setdefault(int(line_id.GetValue(i)), []).append(lines.GetPoint(i)[2])
    band = (zmin + 0.15 * height, zmax - 0.3 * height)
    features = [ConstraintRegion(Input=edges, Role='FeatureLine', SelectionMode='ArrayRange',  # noqa: F821
                                 SelectionArray=['POINTS', 'LineId'], Range=[line, line])
                for line, zs in sorted(z_of.items())
                if line >= 0 and len(zs) >= 8 and band[0] <= min(zs) and max(zs) <= band[1]]
    planar = box_region(part, 'Planarity', [xmin - margin, ymin - margin, (zmin + zmax) / 2],
                        [xmin + 1e-3 * height, ymax + margin, zmax - 0.25 * height])
    return planar, features


def update_deformation(deformed):
    """Updates a deformation (MLS Deform, Shell Deform) and raises RuntimeError with the filter's
    message if it failed: a failed deformation's output is its unchanged input carrying a
    'DeformationError' field-data string (the same message goes to the output window)."""
    deformed.UpdatePipeline()
    error = deformed.GetDataInformation().GetFieldDataInformation().GetArrayInformation('DeformationError')
    if error is not None:
        raise RuntimeError('%s failed: %s' % (deformed.GetXMLLabel(), error.GetStringValue(0)))


def report_constraints(deformed):
    """Prints one line per constraint region of a deformation (type, points, residual relative to
    the diagonal, iterations, converged) and returns the output's field data."""
    from paraview import servermanager
    update_deformation(deformed)
    field = servermanager.Fetch(deformed).GetFieldData()
    types = field.GetAbstractArray('ConstraintType')
    for t in range(types.GetNumberOfValues()):
        print('%s: %d points, residual %.2e of the diagonal, %d iterations, converged %d' % (
            types.GetValue(t), field.GetArray('ConstraintPoints').GetValue(t), field.GetArray('ConstraintResidual').GetValue(t),
            field.GetArray('ConstraintIterations').GetValue(t), field.GetArray('ConstraintConverged').GetValue(t)))
    return field


def save_side_by_side(sources, colors, bounds, path, resolution=(1200, 600), direction=(0.0, -1.0, 0.0), up=(0.0, 0.0, 1.0)):
    """Renders each source in its own view, colored by the point or cell array named in colors
    (None: plain; Displacement by magnitude), all seen along direction with the same parallel
    camera fitted to bounds, and saves them as one PNG."""
    xmin, xmax, ymin, ymax, zmin, zmax = bounds
    size = max(xmax - xmin, ymax - ymin, zmax - zmin)
    center = [(xmin + xmax) / 2, (ymin + ymax) / 2, (zmin + zmax) / 2]
    layout = CreateLayout('side by side')
    cell = 0
    for index, (source, color) in enumerate(zip(sources, colors)):
        view = CreateView('RenderView')
        if index + 1 < len(sources):  # equal columns: split off 1/(views left) on the left
            left = layout.SplitHorizontal(cell, 1.0 / (len(sources) - index))
            layout.AssignView(left, view)
            cell = left + 1
        else:
            layout.AssignView(cell, view)
        view.OrientationAxesVisibility = 0
        display = Show(source, view)
        if color:
            displacement = color == 'Displacement'
            ColorBy(display, ('POINTS', color, 'Magnitude') if displacement else ('CELLS', color))
            display.SetScalarBarVisibility(view, True)
            bar = GetScalarBar(GetColorTransferFunction(color), view)
            bar.WindowLocation = 'Any Location'
            bar.Position = [0.72, 0.1]
            bar.ScalarBarLength = 0.5
            bar.RangeLabelFormat = '%.3f' if displacement else '%.0f'
            bar.Title = '|Displacement|' if displacement else color
            bar.ComponentTitle = ''
        view.CameraFocalPoint = center
        view.CameraPosition = [c + 4 * size * d for c, d in zip(center, direction)]
        view.CameraViewUp = list(up)
        view.CameraParallelProjection = 1
        view.CameraParallelScale = 0.75 * (zmax - zmin if up[2] else size)
    SaveScreenshot(path, layout, ImageResolution=list(resolution))
