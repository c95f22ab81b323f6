"""Paper Fig. 8: the fandisk with its bottom fixed and its top moved sideways, first without
constraints, then keeping the sharp feature lines of the bent band (similarity) and the upper part
of its planar left face (planarity). Prints the constraint residuals and writes
fandisk_constraints.png (original, unconstrained, constrained) and the constrained mesh.

    xvfb-run -a -s "-noreset" pvbatch deform_fandisk_constrained.py PLUGIN FANDISK.off OUTPUT_DIR
"""
import os
import sys

from paraview.simple import FeatureEdges, ProgrammableFilter, SaveData
from paraview import servermanager

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fandisk_scene as scene  # noqa: E402

part, bounds, out_dir = scene.open_fandisk()
xmin, xmax, ymin, ymax, zmin, zmax = bounds
height = zmax - zmin
margin = 0.01 * height
fixed, handle = scene.fixed_and_handle(part, bounds)

# Feature lines: the sharp edges (feature angle 30 degrees), split into lines at their junctions
# (a point array LineId, -1 at junctions), and every line lying in the band that bends.
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
edges = ProgrammableFilter(Input=FeatureEdges(Input=part, BoundaryEdges=0, FeatureEdges=1, NonManifoldEdges=0,
                                              ManifoldEdges=0, FeatureAngle=30), Script=SPLIT_LINES)
lines = servermanager.Fetch(edges)
line_id = lines.GetPointData().GetArray('LineId')
z_of = {}
for i in range(lines.GetNumberOfPoints()):
    z_of.setdefault(int(line_id.GetValue(i)), []).append(lines.GetPoint(i)[2])
band = (zmin + 0.15 * height, zmax - 0.3 * height)
features = [scene.ConstraintRegion(Input=edges, Role='FeatureLine', SelectionMode='ArrayRange',
                             SelectionArray=['POINTS', 'LineId'], Range=[line, line])
            for line, zs in sorted(z_of.items())
            if line >= 0 and len(zs) >= 8 and band[0] <= min(zs) and max(zs) <= band[1]]
# Planarity: the upper half of the planar face at x = xmin.
planar = scene.box_region(part, 'Planarity', [xmin - margin, ymin - margin, (zmin + zmax) / 2],
                          [xmin + 1e-3 * height, ymax + margin, zmax - 0.25 * height])

free = scene.MLSDeform(Input=part, Regions=[fixed, handle])
scene.update_deformation(free)
kept = scene.MLSDeform(Input=part, Regions=[fixed, handle, planar] + features)
field = scene.report_constraints(kept)
print('handle residual %.2e, fixed residual %.2e (handle moved by %.3g), solve %.0f ms' % (
    field.GetArray('HandleResidual').GetValue(0), field.GetArray('FixedResidual').GetValue(0), 0.15 * height,
    1000 * field.GetArray('SolveTime').GetValue(0)))

result = os.path.join(out_dir, 'fandisk_constrained.vtp')
SaveData(result, proxy=kept)
print('wrote', result)
picture = os.path.join(out_dir, 'fandisk_constraints.png')
scene.save_side_by_side([part, free, kept], [None, 'Displacement', 'Displacement'], bounds, picture, resolution=(1500, 500))
print('wrote', picture)
