"""Paper Fig. 10: the joint deformed with automatically detected primitives kept. Primitive
Detector finds the planes and cylinders of the part; the bottom is fixed, the top (the upper
end of the bored cylinder) is lifted as the handle, and every detected primitive is kept by a
Constraint Region (SelectionMode Primitive, Role FromPrimitive: planes stay planes, cylinders
cylinders). Prints the primitives and the constraint residuals and writes joint_primitives.png
(detected primitives, deformation without and with them) and the constrained mesh.

    xvfb-run -a -s "-noreset" pvbatch deform_joint_primitives.py PLUGIN JOINT.off OUTPUT_DIR
"""
import os
import sys

from paraview import servermanager
from paraview.simple import SaveData

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fandisk_scene as scene  # noqa: E402  (the plugin loader, regions and pictures)

part, bounds, out_dir = scene.open_fandisk()
xmin, xmax, ymin, ymax, zmin, zmax = bounds
height = ymax - ymin
margin = 0.01 * height
lift = 0.15 * height

detector = scene.PrimitiveDetector(Input=part)
table = servermanager.Fetch(detector, idx=1)
for row in range(table.GetNumberOfRows()):
    value = lambda column: table.GetValueByName(row, column).ToDouble()
    print('primitive %d: %-8s %3d faces, RMS distance %.1e%s' % (
        row, table.GetValueByName(row, 'Type').ToString(), value('Faces'), value('RMSDistance'),
        ', radius %.4g' % value('Radius') if table.GetValueByName(row, 'Type').ToString() == 'Cylinder' else ''))

fixed = scene.box_region(detector, 'Fixed', [xmin - margin, ymin - margin, zmin - margin], [xmax + margin, ymin + 0.05 * height, zmax + margin])
handle = scene.box_region(detector, 'Handle', [xmin - margin, ymax - 0.2 * height, zmin - margin], [xmax + margin, ymax + margin, zmax + margin],
                          Translation=[0.0, lift, 0.0])
kept = [scene.ConstraintRegion(Input=detector, SelectionMode='Primitive', Role='FromPrimitive', PrimitiveId=p)
        for p in range(table.GetNumberOfRows())]

free = scene.MLSDeform(Input=detector, Regions=[fixed, handle])
scene.update_deformation(free)
constrained = scene.MLSDeform(Input=detector, Regions=[fixed, handle] + kept)
field = scene.report_constraints(constrained)
print('handle residual %.2e (lifted by %.3g), fixed residual %.2e' % (
    field.GetArray('HandleResidual').GetValue(0), lift, field.GetArray('FixedResidual').GetValue(0)))

result = os.path.join(out_dir, 'joint_primitives.vtp')
SaveData(result, proxy=constrained)
print('wrote', result)
picture = os.path.join(out_dir, 'joint_primitives.png')
scene.save_side_by_side([detector, free, constrained], ['PrimitiveId', 'Displacement', 'Displacement'], bounds, picture,
                        resolution=(1500, 550), direction=(0.55, 0.35, 0.76), up=(0.0, 1.0, 0.0))
print('wrote', picture)
