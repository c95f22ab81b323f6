"""Deforms the fandisk part (paper Fig. 8, unconstrained): the bottom is fixed, the top handle is
moved to the side, and the result is written as a .vtp file and a before/after picture.

    pvbatch deform_fandisk.py PLUGIN FANDISK.off OUTPUT_DIR      (rendering needs a display:
    xvfb-run -a pvbatch ...)  or  pvpython deform_fandisk.py ...
"""
import os
import sys

from paraview.simple import SaveData
from paraview import servermanager

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fandisk_scene as scene  # noqa: E402

part, bounds, out_dir = scene.open_fandisk()
height = bounds[5] - bounds[4]
fixed, handle = scene.fixed_and_handle(part, bounds)

deformed = scene.MLSDeform(Input=part, Regions=[fixed, handle])
scene.update_deformation(deformed)  # raises with the filter's message if the deformation failed
field = servermanager.Fetch(deformed).GetFieldData()
summary = {name: field.GetArray(name).GetValue(0) for name in
           ('NumberOfSamples', 'NumberOfIntegrationPoints', 'SetupTime', 'SolveTime',
            'HandleResidual', 'FixedResidual')}
print('fandisk: %d points, k = %d, N = %d, set-up %.2f s, solve %.1f ms, handle residual %.2g, '
      'fixed residual %.2g (handle moved by %.3g)' % (
          part.GetDataInformation().GetNumberOfPoints(), summary['NumberOfSamples'],
          summary['NumberOfIntegrationPoints'], summary['SetupTime'], 1000 * summary['SolveTime'],
          summary['HandleResidual'], summary['FixedResidual'], 0.15 * height))

result = os.path.join(out_dir, 'fandisk_deformed.vtp')
SaveData(result, proxy=deformed)
print('wrote', result)

# Before (left) and after (right), colored by the displacement magnitude.
picture = os.path.join(out_dir, 'fandisk_deformed.png')
scene.save_side_by_side([part, deformed], [None, 'Displacement'], bounds, picture)
print('wrote', picture)
