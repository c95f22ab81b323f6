"""Run inside the paraview GUI (paraview --dr --script=test_gui_held_input.py): issue 54, point 1.
No input is dropped or reordered during an update. With Auto Apply on, the handle box's centre is
dragged with the X server's mouse (xinput: XTest), and the mouse is released straight after the
last move: while the update that move started runs (from the deformation's StartEvent, before its
progress reports process events). The box must end inactive, the handle where the drag left it,
and the whole drag one undo step that undoes it. Then keys typed into a line edit during an
update must all arrive, in order, after the ones typed before it. Writes 'ok' or the failures to
MLSDEFORM_GUI_RESULT."""
import os
import time

import checks  # Testing/Python, on PYTHONPATH
from checks import check, write_result

# The box's transform round trip and the motion fields' display: 1e-9 of the part's size.
TOLERANCE = 1e-9
# Seconds for the X server's events to reach the application's connection (read by Qt's xcb
# thread) before the update goes on to its first progress report, where events are processed.
ARRIVAL = 0.1

try:
    from PyQt5.QtWidgets import QApplication, QLineEdit
    import paraview.simple as pvs
    from paraview.modules.vtkRemotingSettings import vtkPVGeneralSettings
    import fandisk_scene as scene  # Examples/, on PYTHONPATH
    import gui
    import xinput

    scene.load_plugin(os.environ['MLSDEFORM_PLUGIN'])
    app = QApplication.instance()

    def settle(until=lambda: False, seconds=10.0):
        checks.settle(app, until, seconds)

    fandisk = gui.FandiskHandle(scene)
    fandisk.oblique()
    settle(seconds=0.5)
    part, bounds, height, handle, deformed, view = (fandisk.part, fandisk.bounds, fandisk.height, fandisk.handle,
                                                    fandisk.deformed, fandisk.view)
    representation = fandisk.representation
    box_bounds = representation.GetBounds()
    x, y = gui.screen_point(view, [(box_bounds[2 * i] + box_bounds[2 * i + 1]) / 2 for i in range(3)])

    # the deformation's updates: counted, and the release injected into the one the last move starts
    algorithm = deformed.GetClientSideObject()
    updates, injected = [], []

    def started(caller, event):
        updates.append(time.time())
        if inject:
            action = inject.pop(0)
            action()
            injected.append(time.time())
            xinput.wait(ARRIVAL)
    inject = []
    algorithm.AddObserver('StartEvent', started)

    settings = vtkPVGeneralSettings.GetInstance()
    auto_apply = settings.GetAutoApply()
    settings.SetAutoApply(True)
    xinput.move(x, y, wait=0.05)
    xinput.press(wait=0.05)
    settle(lambda: representation.GetInteractionState() != 0, seconds=2.0)
    check(representation.GetInteractionState() != 0, 'the press grabbed the handle box (interaction state %d)'
          % representation.GetInteractionState())
    for k in (1, 2):  # moves that are each applied before the next
        count = len(updates)
        xinput.move(x, y - 15 * k, wait=0.05)
        settle(lambda: len(updates) > count and not algorithm.GetAbortExecute(), seconds=5.0)
        settle(seconds=0.3)
    moved = list(handle.Translation)
    check(moved[2] > 0, 'the drag moved the handle up: Translation %s' % moved)
    # the last move, and the release straight after it, while the move's update runs
    inject.append(lambda: xinput.release())
    count = len(updates)
    xinput.move(x, y - 45)
    settle(lambda: bool(injected) and handle.Dragging == 0, seconds=10.0)
    settle(seconds=0.5)
    check(bool(injected), 'the release was made during the last move\'s update')
    left = list(handle.Translation)
    check(left[2] > moved[2], 'the last move was applied: Translation %s, before it %s' % (left, moved))
    check(representation.GetInteractionState() == 0, 'the box ends inactive after the release (interaction state %d)'
          % representation.GetInteractionState())
    check(handle.Dragging == 0, 'the region is no longer Dragging')
    # the pointer moves on with no button held: the box stays where the drag left it
    xinput.move(x + 40, y - 90, wait=0.05)
    settle(seconds=1.0)
    check(max(abs(a - b) for a, b in zip(handle.Translation, left)) <= TOLERANCE * height,
          'the box does not follow the pointer after the release: Translation %s, left at %s' % (list(handle.Translation), left))
    # the model shows the handle where the drag left it: its points displaced by the Translation
    # (Exact Targets: to the solve's round-off)
    output = algorithm.GetOutputDataObject(0)
    rest = part.GetClientSideObject().GetOutputDataObject(0).GetPoints()
    moved_by = output.GetPointData().GetArray('Displacement')
    top = bounds[5] - 0.25 * height
    misses = [max(abs(moved_by.GetComponent(i, c) - left[c]) for c in range(3))
              for i in range(rest.GetNumberOfPoints()) if rest.GetPoint(i)[2] >= top]
    check(bool(misses) and max(misses) <= 1e-6 * height, 'the model shows where the drag left the handle: its %d points '
          'moved by the Translation to %.2g' % (len(misses), max(misses) if misses else float('nan')))
    undo = gui.action('actionEditUndo')
    check(undo.isEnabled() and 'Move Handle' in undo.text(), 'Edit > Undo offers the drag: "%s", enabled %s'
          % (undo.text(), undo.isEnabled()))
    undo.trigger()
    settle(lambda: abs(handle.Translation[2]) <= TOLERANCE * height)
    check(max(abs(t) for t in handle.Translation) <= TOLERANCE * height, 'one Undo undoes the whole drag: Translation %s'
          % list(handle.Translation))
    settings.SetAutoApply(auto_apply)

    # keys typed before an update, during it and after it reach their line edit in order
    edit = QLineEdit()
    edit.setObjectName('typing')
    edit.resize(300, 30)
    edit.show()
    edit.activateWindow()
    edit.setFocus()
    settle(seconds=0.5)
    ex, ey = xinput.centre(edit)
    xinput.click(ex, ey, wait=0.05)  # the pointer stays there: the keyboard's focus follows it without a window manager
    xinput.type_text('x', wait=0.05)
    settle(lambda: edit.text() == 'x', seconds=2.0)
    inject.append(lambda: xinput.type_text('abc'))
    deformed.NumberOfSamples = 350
    pvs.Render(view)  # inside: the keys, typed at the update's start
    check(bool(inject) is False, 'the keys were typed during the update')
    xinput.type_text('z', wait=0.05)
    settle(lambda: edit.text() == 'xabcz', seconds=3.0)
    check(edit.text() == 'xabcz', 'keys typed before, during and after an update all arrive in order: "%s", '
          'expected "xabcz"' % edit.text())
    edit.close()
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], error)
