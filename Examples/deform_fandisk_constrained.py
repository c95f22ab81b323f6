"""Paper Fig. 8: the fandisk with its bottom fixed and its top moved sideways, first without
constraints, then keeping the sharp feature lines of the bent band (similarity) and the upper part
of its planar left face (planarity). Prints the constraint residuals and writes
fandisk_constraints.png (original, unconstrained, constrained) and the constrained mesh.

    xvfb-run -a -s "-noreset" pvbatch deform_fandisk_constrained.py PLUGIN FANDISK.off OUTPUT_DIR
"""
import os
import sys

from paraview.simple import SaveData

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fandisk_scene as scene  # noqa: E402

part, bounds, out_dir = scene.open_fandisk()
fixed, handle = scene.fixed_and_handle(part, bounds)
planar, features = scene.fig8_constraints(part, bounds)
height = bounds[5] - bounds[4]

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
