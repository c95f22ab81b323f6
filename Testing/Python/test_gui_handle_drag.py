"""Run inside the paraview GUI (paraview --dr --script=test_gui_handle_drag.py): issue 32, points 1,
2 and 6. The Handle region of the fandisk shows its handle box, outline and handles in the Handle
colour (red), and not its selection box (issue 54: one box at a time). With Auto Apply on, the handle
box is dragged up in five motion events, as vtkBoxWidget2 reports a drag (start, moves, end; each
move is applied while the drag goes on). Edit > Undo once must return the handle to where it was
before the drag, and Edit > Redo once must bring the whole drag back. Then the model is made
opaque white: the box's centre sphere, inside it at the pivot, must show at its pixel, and a mouse
drag on that pixel (press, moves, release through the view's interactor) must move the handle.
Saved and loaded as a state, the Handle shows its handle box again, red, alone.
Writes 'ok' or the failures to MLSDEFORM_GUI_RESULT."""
import os

import checks  # Testing/Python, on PYTHONPATH
from checks import check, write_result

STEPS = 5
# The box's transform round trip (vtkBoxRepresentation::GetTransform and the Euler angles of
# HandleMotion): ~1e-14 of the part's size; undo and redo restore the saved values exactly.
TOLERANCE = 1e-9

try:
    from PyQt5.QtWidgets import QAction, QApplication
    import paraview.simple as pvs
    from paraview.modules.vtkRemotingSettings import vtkPVGeneralSettings
    from paraview.vtk import vtkTransform
    import fandisk_scene as scene  # Examples/, on PYTHONPATH
    import gui

    scene.load_plugin(os.environ['MLSDEFORM_PLUGIN'])
    app = QApplication.instance()

    def settle(until=lambda: False, seconds=10.0):
        checks.settle(app, until, seconds)

    def edit_action(name):
        """The main window's Edit > Undo or Redo."""
        actions = [a for w in app.topLevelWidgets() if w.objectName() == 'pqClientMainWindow'
                   for a in w.findChildren(QAction) if a.objectName() == 'actionEdit' + name]
        if not actions:
            raise RuntimeError('no Edit > %s action' % name)
        return actions[0]

    def near(values, expected):
        return max(abs(a - b) for a, b in zip(values, expected)) <= TOLERANCE * max(1.0, height)

    fandisk = gui.FandiskHandle(scene)
    part, bounds, height, fixed, handle, deformed, view = (fandisk.part, fandisk.bounds, fandisk.height, fandisk.fixed,
                                                           fandisk.handle, fandisk.deformed, fandisk.view)
    widget, representation = fandisk.box, fandisk.representation
    red = [0.9, 0.1, 0.1]  # the Handle's colour (Filters/Vocabulary/RegionRoles.h)
    for part_name in ('Outline', 'Handle'):
        colour = list(getattr(representation, 'Get%sProperty' % part_name)().GetColor())
        check(colour == red, 'the handle box %s is drawn in %s, the Handle colour is %s' % (part_name.lower(), colour, red))

    settings = vtkPVGeneralSettings.GetInstance()
    auto_apply = settings.GetAutoApply()
    settings.SetAutoApply(True)
    # the drag: up by 2% of the height per motion event, each applied before the next
    step = 0.02 * height
    start = vtkTransform()
    representation.GetTransform(start)
    widget.GetWidget().InvokeEvent('StartInteractionEvent')
    for k in range(1, STEPS + 1):
        moved = vtkTransform()
        moved.PostMultiply()
        moved.Concatenate(start)
        moved.Translate(0, 0, k * step)
        representation.SetTransform(moved)
        widget.GetWidget().InvokeEvent('InteractionEvent')
        settle(lambda: near(handle.Translation, [0, 0, k * step]))
        check(near(handle.Translation, [0, 0, k * step]), 'motion event %d applied during the drag: Translation %s'
              % (k, list(handle.Translation)))
    widget.GetWidget().InvokeEvent('EndInteractionEvent')
    settle(seconds=1.0)
    dragged = [0, 0, STEPS * step]
    check(near(handle.Translation, dragged), 'after the drag: Translation %s, expected %s'
          % (list(handle.Translation), dragged))

    undo, redo = edit_action('Undo'), edit_action('Redo')
    check(undo.isEnabled() and 'Move Handle' in undo.text(), 'Edit > Undo offers the drag: "%s", enabled %s'
          % (undo.text(), undo.isEnabled()))
    undo.trigger()
    settle(lambda: near(handle.Translation, [0, 0, 0]))
    check(near(handle.Translation, [0, 0, 0]), 'one Undo returns the handle: Translation %s, expected 0'
          % list(handle.Translation))
    redo.trigger()
    settle(lambda: near(handle.Translation, dragged))
    check(near(handle.Translation, dragged), 'one Redo brings the whole drag back: Translation %s, expected %s'
          % (list(handle.Translation), dragged))

    # Point 1: the box's centre sphere, at the pivot inside the opaque model, is drawn over it and
    # dragged with the mouse. The model white and the region's points hidden: the pixel at the
    # centre is the sphere's red only when the box is drawn on top.
    look = pvs.GetDisplayProperties(deformed, view)
    pvs.ColorBy(look, None)
    look.DiffuseColor, look.AmbientColor, look.Opacity = [1, 1, 1], [1, 1, 1], 1.0
    pvs.Hide(handle, view)
    pvs.Hide(fixed, view)
    pvs.SetActiveSource(handle)
    view.OrientationAxesVisibility = 0
    view.CameraPosition = [1.5 * height, -3 * height, 1.2 * height]  # oblique: no face handle in front of the centre
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    pvs.Render(view)
    settle(seconds=0.5)
    bounds = representation.GetBounds()
    centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
    renderer = view.GetRenderer()
    renderer.SetWorldPoint(centre + [1.0])
    renderer.WorldToDisplay()
    x, y = [int(round(c)) for c in renderer.GetDisplayPoint()[:2]]
    from paraview.vtk.vtkRenderingCore import vtkWindowToImageFilter
    grab = vtkWindowToImageFilter()
    grab.SetInput(view.GetRenderWindow())
    grab.ReadFrontBufferOff()
    grab.ShouldRerenderOn()
    grab.Update()
    pixel = [grab.GetOutput().GetScalarComponentAsDouble(x, y, 0, c) / 255 for c in range(3)]
    # the sphere's yellow (1, 0.85, 0), shaded: blue well below red and green; the white model
    # would be grey
    check(pixel[0] > 0.4 and pixel[1] > 0.3 and pixel[0] > 2 * pixel[2] and pixel[1] > 2 * pixel[2],
          'the centre sphere at the pivot, inside the opaque model, is drawn over it: pixel (%d, %d) is %s'
          % (x, y, [round(c, 2) for c in pixel]))
    # a mouse drag on it, 30 pixels up, through the view's interactor: the handle moves up
    from paraview.vtk.vtkInteractionWidgets import vtkBoxRepresentation
    picked = representation.ComputeInteractionState(x, y, 0)
    check(picked == vtkBoxRepresentation.Translating, 'the pixel picks the centre sphere: interaction state %d, Translating is %d'
          % (picked, vtkBoxRepresentation.Translating))
    before = list(handle.Translation)
    interactor = widget.GetWidget().GetInteractor()  # the view's, as the widget listens to it
    for event, position in (('MouseMoveEvent', (x, y)), ('LeftButtonPressEvent', (x, y)),
                            ('MouseMoveEvent', (x, y + 10)), ('MouseMoveEvent', (x, y + 20)),
                            ('MouseMoveEvent', (x, y + 30)), ('LeftButtonReleaseEvent', (x, y + 30))):
        interactor.SetEventInformation(position[0], position[1], 0, 0, '\0', 0)
        interactor.InvokeEvent(event)
        settle(seconds=0.2)
    settle(lambda: handle.Translation[2] > before[2] + 0.01 * height)
    check(handle.Translation[2] > before[2] + 0.01 * height,
          'the mouse dragged the centre sphere up: Translation %s, before %s' % (list(handle.Translation), before))
    settings.SetAutoApply(auto_apply)

    # Point 2, restored from a state file: the Handle's box comes back red, alone
    import tempfile
    state = os.path.join(tempfile.mkdtemp(), 'drag.pvsm')
    pvs.SaveState(state)
    names = {proxy: name for (name, _), proxy in pvs.GetSources().items()}
    handle_name = names[handle]
    for proxy in (deformed, handle, fixed, part):
        pvs.Delete(proxy)
    settle(seconds=0.5)
    pvs.LoadState(state)
    pvs.SetActiveSource(pvs.FindSource(handle_name))
    settle(seconds=1.0)
    reloaded, shown = gui.shown_boxes(pvs.GetActiveView())
    check(len(reloaded) == 1 and len(shown) == 1, 'after Load State: the handle box shown alone (%d handle boxes of %d)'
          % (len(reloaded), len(shown)))
    if reloaded:
        colour = list(reloaded[0].GetRepresentationProxy().GetClientSideObject().GetOutlineProperty().GetColor())
        check(colour == red, 'after Load State: the handle box is drawn in %s (the Handle colour %s)' % (colour, red))
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], error)
