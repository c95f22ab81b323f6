"""Deforms the fandisk part (paper Fig. 8, unconstrained): the bottom is fixed, the top handle is
moved to the side, and the result is written as a .vtp file and a before/after picture.

    pvbatch deform_fandisk.py PLUGIN FANDISK.off OUTPUT_DIR      (rendering needs a display:
    xvfb-run -a pvbatch ...)  or  pvpython deform_fandisk.py ...
"""
import os
import sys

from paraview.simple import (AssignViewToLayout, ColorBy, CreateLayout, CreateView,
                             GetColorTransferFunction, GetScalarBar, LoadPlugin, OpenDataFile,
                             SaveData, SaveScreenshot, Show)
from paraview import servermanager

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
layout = CreateLayout('fandisk')
views = []
for source, colored in ((part, False), (deformed, True)):
    view = CreateView('RenderView')
    AssignViewToLayout(view=view, layout=layout)
    view.OrientationAxesVisibility = 0
    display = Show(source, view)
    if colored:
        ColorBy(display, ('POINTS', 'Displacement', 'Magnitude'))
        display.SetScalarBarVisibility(view, True)
        bar = GetScalarBar(GetColorTransferFunction('Displacement'), view)
        bar.WindowLocation = 'Any Location'
        bar.Position = [0.72, 0.1]
        bar.ScalarBarLength = 0.5
        bar.RangeLabelFormat = '%.3f'
        bar.Title = '|Displacement|'
        bar.ComponentTitle = ''
    views.append(view)
# One camera for both views, so that the motion shows.
center = [(xmin + xmax) / 2, (ymin + ymax) / 2, (zmin + zmax) / 2]
for view in views:
    view.CameraFocalPoint = center
    view.CameraPosition = [center[0], center[1] - 4 * height, center[2]]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 0.75 * height
picture = os.path.join(out_dir, 'fandisk_deformed.png')
SaveScreenshot(picture, layout, ImageResolution=[1200, 600])
print('wrote', picture)
