"""Side-by-side pictures of pipeline outputs with one camera, shared by the example scripts."""
from paraview.simple import (ColorBy, CreateLayout, CreateView, GetColorTransferFunction,
                             GetScalarBar, SaveScreenshot, Show)


def save_side_by_side(sources, colored, bounds, path, resolution=(1200, 600)):
    """Renders each source in its own view (colored by |Displacement| where colored is true),
    all seen from -y with the same parallel camera fitted to bounds, and saves them as one PNG."""
    xmin, xmax, ymin, ymax, zmin, zmax = bounds
    height = zmax - zmin
    center = [(xmin + xmax) / 2, (ymin + ymax) / 2, (zmin + zmax) / 2]
    layout = CreateLayout('side by side')
    cell = 0
    for index, (source, color) in enumerate(zip(sources, colored)):
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
            ColorBy(display, ('POINTS', 'Displacement', 'Magnitude'))
            display.SetScalarBarVisibility(view, True)
            bar = GetScalarBar(GetColorTransferFunction('Displacement'), view)
            bar.WindowLocation = 'Any Location'
            bar.Position = [0.72, 0.1]
            bar.ScalarBarLength = 0.5
            bar.RangeLabelFormat = '%.3f'
            bar.Title = '|Displacement|'
            bar.ComponentTitle = ''
        view.CameraFocalPoint = center
        view.CameraPosition = [center[0], center[1] - 4 * height, center[2]]
        view.CameraViewUp = [0.0, 0.0, 1.0]
        view.CameraParallelProjection = 1
        view.CameraParallelScale = 0.75 * height
    SaveScreenshot(path, layout, ImageResolution=list(resolution))
