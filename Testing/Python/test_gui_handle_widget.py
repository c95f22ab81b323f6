"""Issue 13 point 1 in the GUI: the Constraint Region's handle box moves the handle. Two runs:

    paraview --dr --script=test_gui_handle_widget.py --test-script=handle_widget.xml
             --test-baseline=... --exit
        builds the fandisk pipeline (environment: MLSDEFORM_PLUGIN, MLSDEFORM_DATA_DIR,
        MLSDEFORM_GUI_RESULT; Examples/ on PYTHONPATH in both runs) with the handle region active, checks that its box surrounds the
        selected positions centred on the pivot, then moves the box as a drag does (the box's
        representation is transformed and the widget fires its interaction events): up by 10% of
        the part's height and 20 degrees about the view axis about the box centre (after a typed
        translation has moved the box and been typed back). The Translation and Rotation fields
        must take that motion before Apply, and with Auto Apply on it is applied before the drag
        ends. Then the view must show it (issue 54, point 6: what the picture is about, the same
        on any CPU): the box's outline at its edges and its centre sphere at the moved pivot, drawn
        over the model, and the region's points drawn where the handle goes. The recorded events
        then press Apply (nothing is left to apply) and save the state.
    pvpython test_gui_handle_widget.py PLUGIN DATA_DIR RESULT STATE
        checks the GUI's result file, that the saved state holds the applied motion, and that the
        state's deformation equals the deformation with that motion typed in pvpython.
"""
import os
import sys
import xml.etree.ElementTree as ElementTree

import paraview.simple as pvs

import fandisk_scene as scene  # Examples/, on PYTHONPATH

in_gui = 'MLSDEFORM_GUI_RESULT' in os.environ
plugin, data = (os.environ['MLSDEFORM_PLUGIN'], os.environ['MLSDEFORM_DATA_DIR']) if in_gui else sys.argv[1:3]
scene.load_plugin(plugin)

# The motion the box is given: up (z) by 10% of the height, 20 degrees about z (the view axis).
LIFT, TURN = 0.1, 20.0
# The box's points are transformed and its transform recovered (vtkBoxRepresentation::GetTransform)
# through ~20 operations on coordinates of size ~1: ~1e-14; the Euler angles from it: ~1e-13 degrees.
TOLERANCE = 1e-9


def fandisk_pipeline():
    """The fandisk of Examples/fandisk_scene.py (bottom 10% Fixed, top 25% the Handle), unmoved."""
    part = pvs.OpenDataFile(os.path.join(data, 'fandisk.off'))
    part.UpdatePipeline()
    bounds = part.GetDataInformation().GetBounds()
    fixed, handle = scene.fixed_and_handle(part, bounds)
    handle.Translation = [0, 0, 0]
    deformed = scene.MLSDeform(Input=part, Regions=[fixed, handle])
    return part, fixed, handle, deformed, bounds[5] - bounds[4]


def gui_run():
    from paraview.vtk import vtkTransform
    failures = []
    part, fixed, handle, deformed, height = fandisk_pipeline()
    view = pvs.GetActiveViewOrCreate('RenderView')
    shown = {source: pvs.Show(source, view) for source in (deformed, fixed, handle)}
    # the default look (issue 13 point 3): the model coloured by displacement, the regions as
    # points in their role's colour (Plugin/pqOutputColoring.cxx)
    if list(shown[deformed].ColorArrayName) != ['POINTS', 'Displacement']:
        failures.append('the deformed model is coloured by %s' % list(shown[deformed].ColorArrayName))
    for region, colour in ((fixed, [0.15, 0.35, 1.0]), (handle, [0.9, 0.1, 0.1])):
        look = shown[region]
        if look.Representation != 'Points' or list(look.DiffuseColor) != colour or look.ColorArrayName[1]:
            failures.append('the %s region is drawn as %s in %s coloured by %s' % (
                region.Role, look.Representation, list(look.DiffuseColor), list(look.ColorArrayName)))
    handle.UpdatePipeline()
    pvs.SetActiveSource(handle)
    pvs.Render(view)
    boxes = [p for p in view.GetProperty('HiddenRepresentations')
             if (p.SMProxy.GetLogName() or '').startswith('handle motion box of ')]
    active = [b for b in boxes if b.SMProxy.GetProperty('Visibility').GetElement(0)]
    if len(active) != 1:
        return failures + ['expected one visible handle box, found %d of %d' % (len(active), len(boxes))]
    widget = active[0].SMProxy
    representation = widget.GetRepresentationProxy().GetClientSideObject()
    handle.UpdatePropertyInformation()
    pivot = list(handle.GetProperty('PivotInfo'))
    lower_upper = representation.GetBounds()
    centre = [(lower_upper[2 * i] + lower_upper[2 * i + 1]) / 2 for i in range(3)]
    if max(abs(c - p) for c, p in zip(centre, pivot)) > TOLERANCE * height:
        failures.append('the box centre %s is not the pivot %s' % (centre, pivot))
    # typing a translation moves the box by it; typing it back returns the box
    translation = handle.GetProperty('Translation').SMProperty
    for lift, where in ((0.05 * height, 'after typing a translation'), (0.0, 'after typing it back')):
        translation.SetUncheckedElement(2, lift)
        moved = representation.GetBounds()
        moved_centre = [(moved[2 * i] + moved[2 * i + 1]) / 2 for i in range(3)]
        if max(abs(m - c - d) for m, c, d in zip(moved_centre, centre, [0, 0, lift])) > TOLERANCE * height:
            failures.append('the box centre %s is not the pivot moved by %s %s' % (moved_centre, lift, where))
    # a drag: the representation moves, the widget reports the interaction
    transform = vtkTransform()
    representation.GetTransform(transform)
    transform.PostMultiply()
    transform.Translate(-centre[0], -centre[1], -centre[2])
    transform.RotateZ(TURN)
    transform.Translate(centre[0], centre[1], centre[2] + LIFT * height)
    representation.SetTransform(transform)
    for event in ('StartInteractionEvent', 'InteractionEvent'):
        widget.GetWidget().InvokeEvent(event)
    fields = {name: [handle.GetProperty(name).SMProperty.GetUncheckedElement(i) for i in range(3)]
              for name in ('Translation', 'Rotation', 'Scale')}
    expected = {'Translation': [0, 0, LIFT * height], 'Rotation': [0, 0, TURN], 'Scale': [1, 1, 1]}
    for name, values in expected.items():
        if max(abs(a - b) for a, b in zip(fields[name], values)) > TOLERANCE * max(1, height):
            failures.append('%s after the drag is %s, expected %s' % (name, fields[name], values))
    # With Auto Apply on, the step is applied while the drag goes on (before its end event): the
    # region's applied Translation is the step's
    from PyQt5.QtWidgets import QApplication
    from paraview.modules.vtkRemotingSettings import vtkPVGeneralSettings
    settings = vtkPVGeneralSettings.GetInstance()
    settings.SetAutoApply(True)
    for _ in range(100):  # the panel's and Auto Apply's zero-delay timers
        QApplication.processEvents()
    settings.SetAutoApply(False)
    if max(abs(a - b) for a, b in zip(handle.Translation, expected['Translation'])) > TOLERANCE * height:
        failures.append('Auto Apply during the drag applied Translation %s' % list(handle.Translation))
    widget.GetWidget().InvokeEvent('EndInteractionEvent')
    view.CameraPosition = [0, -3 * height, 2 * height]
    view.CameraFocalPoint = pivot
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    return (failures + view_failures(view, representation, handle, shown[handle], height)
            + contrast_failures(view, representation, handle, shown[handle], shown[deformed]))


class Picture:
    """The view's rendered pixels, looked up by world point. Shading differs between CPUs (the
    renderer's reciprocal square roots are approximations of their own on each), so pixels are
    tested for their hue, not their values; a line's pixels lie within half a pixel of its
    projection."""

    def __init__(self, view):
        from paraview.vtk.vtkRenderingCore import vtkWindowToImageFilter
        pvs.Render(view)
        grab = vtkWindowToImageFilter()
        grab.SetInput(view.GetRenderWindow())
        grab.ReadFrontBufferOff()
        grab.ShouldRerenderOn()
        grab.Update()
        self.image = grab.GetOutput()
        self.size = self.image.GetDimensions()
        self.renderer = view.GetRenderer()

    def pixel_of(self, point):
        self.renderer.SetWorldPoint(list(point) + [1.0])
        self.renderer.WorldToDisplay()
        return [int(round(c)) for c in self.renderer.GetDisplayPoint()[:2]]

    def colours_near(self, x, y, reach):
        return [[self.image.GetScalarComponentAsDouble(i, j, 0, c) / 255 for c in range(3)]
                for i in range(max(0, x - reach), min(self.size[0], x + reach + 1))
                for j in range(max(0, y - reach), min(self.size[1], y + reach + 1))]


def red(c):  # the Handle's red (0.9, 0.1, 0.1), shaded
    return c[0] > 0.3 and c[0] > 2 * c[1] and c[0] > 2 * c[2]


def yellow(c):  # the centre sphere's (1, 0.85, 0), shaded
    return c[0] > 0.3 and c[1] > 0.25 and c[0] > 2 * c[2] and c[1] > 2 * c[2]


def dark(c):  # the box's black halo (unlit); the red model's darkest shading keeps its hue
    return max(c) < 0.12


def light(c):  # a white highlight: the red model (no specular) never has green and blue above 0.1
    return c[1] > 0.4 and c[2] > 0.4


# The box's 12 edges by corner (vtkBoxRepresentation's first 8 points).
EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]


def box_points(representation):
    from paraview.vtk.vtkCommonDataModel import vtkPolyData
    box = vtkPolyData()
    representation.GetPolyData(box)  # the moved box: 8 corners, 6 face centres, its centre
    return [box.GetPoint(i) for i in range(15)]


def view_failures(view, representation, handle, points_look, height):
    """What the view shows of the moved handle, from its rendered pixels and its representations."""
    from paraview.vtk.vtkRenderingCore import vtkActor
    failures = []
    picture = Picture(view)
    points = box_points(representation)
    missed = []
    for a, b in EDGES:
        x, y = picture.pixel_of([(p + q) / 2 for p, q in zip(points[a], points[b])])
        if not any(red(c) for c in picture.colours_near(x, y, 1)):
            missed.append((a, b, x, y))
    if missed:
        failures.append('the view shows no red outline at these edges of the moved box (corners, pixel): %s' % missed)
    x, y = picture.pixel_of(points[14])  # the box's centre: the moved pivot
    colour = picture.colours_near(x, y, 0)[0]
    if not yellow(colour):
        failures.append('the view shows no centre sphere at the moved pivot: pixel (%d, %d) is %s' % (x, y, colour))
    # the region's points are drawn where the handle goes: the representation's transform takes
    # each selected position to its target (position + PrescribedDisplacement)
    drawn = vtkActor()
    drawn.SetPosition(list(points_look.Position))
    drawn.SetOrientation(list(points_look.Orientation))
    drawn.SetScale(list(points_look.Scale))
    matrix = drawn.GetMatrix()
    output = handle.GetClientSideObject().GetOutputDataObject(0)
    targets = output.GetPointData().GetArray('PrescribedDisplacement')
    miss = 0.0
    for i in range(output.GetNumberOfPoints()):
        x = list(output.GetPoint(i)) + [1.0]
        moved = [sum(matrix.GetElement(r, c) * x[c] for c in range(4)) for r in range(3)]
        miss = max(miss, max(abs(moved[k] - x[k] - targets.GetComponent(i, k)) for k in range(3)))
    if output.GetNumberOfPoints() == 0 or miss > TOLERANCE * height:
        failures.append('the region\'s %d points are drawn %g from where the handle goes' % (output.GetNumberOfPoints(), miss))
    return failures


def contrast_failures(view, representation, handle, points_look, model_look):
    """Issue 63, point 4: the handle stays visible over a model coloured in the handle's own red
    (the red end of a displacement colour map): each edge of the box has its dark halo beside the
    red line (the halo is 1.5 pixels wide each side of the line: looked for within 3 pixels); the
    region's points show their white highlights; and seen along an axis of the box, the face
    sphere in front of the centre sphere is not drawn over it."""
    failures = []
    colour = list(model_look.ColorArrayName)
    model_look.ColorArrayName = ['POINTS', '']
    model_look.DiffuseColor = model_look.AmbientColor = [0.9, 0.1, 0.1]
    picture = Picture(view)
    points = box_points(representation)
    unhaloed = []
    for a, b in EDGES:
        x, y = picture.pixel_of([(p + q) / 2 for p, q in zip(points[a], points[b])])
        near = picture.colours_near(x, y, 3)
        if not (any(red(c) for c in near) and any(dark(c) for c in near)):
            unhaloed.append((a, b, x, y))
    if unhaloed:
        failures.append('over a red model these edges of the box have no dark halo (corners, pixel): %s' % unhaloed)
    # the highlight of a bead (8 pixels across, SpecularPower 5) lies within 2 pixels of its
    # centre's projection; the region is the part's top, seen from above and in front, so at least
    # a quarter of its points face the camera unhidden
    output = handle.GetClientSideObject().GetOutputDataObject(0)
    targets = output.GetPointData().GetArray('PrescribedDisplacement')
    lit = 0
    for i in range(output.GetNumberOfPoints()):
        x, y = picture.pixel_of([output.GetPoint(i)[k] + targets.GetComponent(i, k) for k in range(3)])
        lit += any(light(c) for c in picture.colours_near(x, y, 2))
    if lit < output.GetNumberOfPoints() / 4:
        failures.append('over a red model only %d of the region\'s %d points show a highlight' % (lit, output.GetNumberOfPoints()))
    # along the box's axis through a face sphere (its point 10, the -y face's centre)
    axis = [f - c for f, c in zip(points[10], points[14])]
    view.CameraFocalPoint = list(points[14])
    view.CameraPosition = [c + 4 * a for c, a in zip(points[14], axis)]
    view.CameraViewUp = [0, 0, 1]
    # the centre sphere is 15 pixels in radius (2 x 1.5 x HandleSize 5), the face sphere in front
    # of it 7.5: pixels 4 pixels diagonally off its centre are the face sphere's if it is drawn, and
    # clear of the centre lines (crossing at the centre)
    picture = Picture(view)
    x, y = picture.pixel_of(points[14])
    seen = [picture.colours_near(x + dx, y + dy, 0)[0] for dx in (-4, 4) for dy in (-4, 4)]
    if not all(yellow(c) for c in seen):
        failures.append('seen along the box\'s axis, the centre sphere at pixel (%d, %d) shows %s: a face sphere is drawn over it'
                        % (x, y, seen))
    model_look.ColorArrayName = colour
    return failures


def pvpython_run(result, state):
    failures = []
    with open(result) as f:
        message = f.read().strip()
    if message != 'ok':
        failures.append('in the GUI: ' + message)
    # the applied motion in the saved state: the handle region's (the one with Role 0)
    regions = [p for p in ElementTree.parse(state).getroot().iter('Proxy')
               if p.get('group') == 'filters' and p.get('type') == 'ConstraintRegion']

    def values(proxy, name):
        prop = [p for p in proxy.iter('Property') if p.get('name') == name][0]
        return [float(e.get('value')) for e in prop.iter('Element')]
    handles = [r for r in regions if values(r, 'Role') == [0.0]]
    _, _, handle, deformed, height = fandisk_pipeline()
    typed = {'Translation': [0, 0, LIFT * height], 'Rotation': [0, 0, TURN], 'Scale': [1, 1, 1]}
    if len(handles) != 1:
        failures.append('expected one handle region in the state, found %d' % len(handles))
    else:
        for name, expected in typed.items():
            applied = values(handles[0], name)
            if max(abs(a - b) for a, b in zip(applied, expected)) > TOLERANCE * max(1, height):
                failures.append('%s applied in the GUI is %s, expected %s' % (name, applied, expected))
    # the GUI's pipeline, loaded from its state, deforms as the typed motion does
    for name, value in typed.items():
        setattr(handle, name, value)
    from paraview import servermanager
    from paraview.vtk.util.numpy_support import vtk_to_numpy
    typed_points = vtk_to_numpy(servermanager.Fetch(deformed).GetPoints().GetData())
    pvs.ResetSession()
    scene.load_plugin(plugin)
    pvs.LoadState(state, data_directory=data)
    gui_deformed = [s for s in pvs.GetSources().values() if s.GetXMLName() == 'MLSDeform'][0]
    gui_points = vtk_to_numpy(servermanager.Fetch(gui_deformed).GetPoints().GetData())
    # the same solve of the same motion: equal up to the motion's round trip through the GUI
    difference = abs(gui_points - typed_points).max() if gui_points.shape == typed_points.shape else float('inf')
    if difference > TOLERANCE * height:
        failures.append('the GUI deformation differs from the typed one by %g' % difference)
    print('\n'.join(failures) or 'ok: the box moved the handle; state and deformation equal the typed motion')
    return failures


if in_gui:
    try:
        message = '\n'.join(gui_run()) or 'ok'
    except Exception as error:  # reported through the result file, the GUI swallows exceptions
        message = 'error: %r' % error
    with open(os.environ['MLSDEFORM_GUI_RESULT'], 'w') as f:
        f.write(message)
else:
    sys.exit(1 if pvpython_run(*sys.argv[3:5]) else 0)
