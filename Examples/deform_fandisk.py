"""Deforms the fandisk part (paper Fig. 8, unconstrained): the bottom is fixed, the top handle is
moved to the side, and the result is written as a .vtp file and a before/after picture.

    pvbatch deform_fandisk.py PLUGIN FANDISK.off OUTPUT_DIR      (rendering needs a display:
    xvfb-run -a pvbatch ...)  or  pvpython deform_fandisk.py ...
"""
import os
import sys

from paraview.simple import LoadPlugin, OpenDataFile, SaveData
from paraview import servermanager

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from views import save_side_by_side  # noqa: E402

plugin, mesh, out_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
os.makedirs(out_dir, exist_ok=True)

part = OpenDataFile(mesh)
part.UpdatePipeline()
xmin, xmax, ymin, ymax, zmin, zmax = part.GetDataInformation().GetBounds()
height = zmax - zmin
margin = 0.01 * height

# Fixed: the bottom 10% of the part. Handle: the top 25%, moved along -x by 15% of the height.
fixed = ConstraintRegion(Input=part, Role='Fixed')
fixed.Region = 'Box'
fixed.Region.Position = [xmin - margin, ymin - margin, zmin - margin]
fixed.Region.Length = [xmax - xmin + 2 * margin, ymax - ymin + 2 * margin, 0.1 * height + margin]

handle = ConstraintRegion(Input=part, Role='Handle')
handle.Region = 'Box'
handle.Region.Position = [xmin - margin, ymin - margin, zmax - 0.25 * height]
handle.Region.Length = [xmax - xmin + 2 * margin, ymax - ymin + 2 * margin, 0.25 * height + margin]
handle.Translation = [-0.15 * height, 0.0, 0.0]

deformed = MLSDeform(Input=part, Regions=[fixed, handle])
deformed.UpdatePipeline()
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
save_side_by_side([part, deformed], [False, True], (xmin, xmax, ymin, ymax, zmin, zmax), picture)
print('wrote', picture)
