"""Run inside the paraview GUI (paraview --dr --script=test_gui_one_box.py): issue 54, point 3. One
box at a time, with the X server's mouse (xinput: XTest). A new Handle region shows its selection
box and no handle box until its first Apply; then the handle box alone. The panel's one choice
("Box in the view": Handle, Selection, None) and the selection box's own Show check box switch
between them, never showing both; a click where the hidden handle box is moves nothing and adds
no undo step; unticking the selection box's Show brings the handle box back. Another role shows
the selection box. The handle box's centre sphere is twice the
face spheres' size, of a colour no role has, and taken by a click even where a face sphere lies in
front of it; the box is at least a quarter as thick as it is long. Writes 'ok' or the failures to
MLSDEFORM_GUI_RESULT."""
import os

import checks  # Testing/Python, on PYTHONPATH
from checks import check, write_result

# Seconds for the X server's events to reach the application (Qt's xcb thread).
ARRIVAL = 0.05
# The handle box's least thickness over its length (Plugin/pqHandleMotionWidget.cxx).
LEAST_ASPECT = 0.25
# The roles' colours (Filters/Vocabulary/RegionRoles.h): red, blue, green, orange.
ROLE_COLOURS = [[0.9, 0.1, 0.1], [0.15, 0.35, 1.0], [0.1, 0.75, 0.2], [1.0, 0.6, 0.0]]

try:
    from PyQt5.QtWidgets import QAction, QApplication, QCheckBox, QPushButton, QRadioButton
    import paraview.simple as pvs
    from vtkmodules.vtkRenderingCore import vtkPropCollection
    import fandisk_scene as scene  # Examples/, on PYTHONPATH
    import gui
    import xinput

    scene.load_plugin(os.environ['MLSDEFORM_PLUGIN'])
    app = QApplication.instance()
    window = gui.activate()

    def settle(until=lambda: False, seconds=5.0):
        checks.settle(app, until, seconds)

    def boxes():
        """(handle boxes shown, selection boxes shown)."""
        handle_boxes, shown = gui.shown_boxes(view)
        return len(handle_boxes), len(shown) - len(handle_boxes)

    def choice():
        return [b.text() for b in window.findChildren(QRadioButton) if b.objectName().startswith('Box') and b.isChecked()
                and b.isVisible()]

    def click(widget, left=None):
        xinput.click(*gui.reveal(widget, left), wait=ARRIVAL)
        settle(seconds=0.5)

    part = pvs.OpenDataFile(os.path.join(os.environ['MLSDEFORM_DATA_DIR'], 'fandisk.off'))
    part.UpdatePipeline()
    bounds = part.GetDataInformation().GetBounds()
    height = bounds[5] - bounds[4]
    view = pvs.GetActiveViewOrCreate('RenderView')
    pvs.Show(part, view)
    view.CameraPosition = [1.5 * height, -3 * height, 1.2 * height]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    # a new region, from Filters > MLS Deformation > Constraint Region: a Handle selecting with a box
    pvs.SetActiveSource(part)
    settle(seconds=0.5)
    [a for a in window.findChildren(QAction) if a.text() == 'Constraint Region'][0].trigger()
    settle(seconds=1.0)
    region = pvs.GetActiveSource()
    check(region.GetXMLName() == 'ConstraintRegion' and region.Role == 'Handle' and region.Region.GetXMLName() == 'Box',
          'the new region is a Handle selecting with a box: %s %s %s' % (region.GetXMLName(), region.Role,
                                                                         region.Region.GetXMLName()))
    # the top quarter, typed once the panel placed its box on the part
    region.Region.Position = [bounds[0] - 0.01, bounds[2] - 0.01, bounds[5] - 0.25 * height]
    region.Region.Length = [bounds[1] - bounds[0] + 0.02, bounds[3] - bounds[2] + 0.02, 0.25 * height + 0.01]
    settle(seconds=0.5)
    check(boxes() == (0, 1), 'a new region shows its selection box and no handle box before its first Apply: %d handle, '
          '%d selection' % boxes())
    apply = [b for b in window.findChildren(QPushButton) if b.objectName() == 'Accept'][0]
    click(apply)
    settle(lambda: boxes()[0] == 1)
    check(region.GetDataInformation().GetNumberOfPoints() > 0, 'the region selects the top: %d points'
          % region.GetDataInformation().GetNumberOfPoints())
    check(boxes() == (1, 0), 'applied, the Handle shows its handle box alone: %d handle, %d selection' % boxes())
    check(choice() == ['Handle'], 'the panel\'s choice of box says Handle: %s' % choice())

    radios = {b.text(): b for b in window.findChildren(QRadioButton) if b.objectName().startswith('Box')}
    click(radios['Selection'])
    check(boxes() == (0, 1), 'Selection chosen: the selection box alone: %d handle, %d selection' % boxes())
    # a click and a drag where the (hidden) handle box's centre is: nothing moves, no undo step
    handle_box = [p.SMProxy for p in view.GetProperty('HiddenRepresentations')
                  if (p.SMProxy.GetLogName() or '').startswith('handle motion box of ')][0]
    representation = handle_box.GetRepresentationProxy().GetClientSideObject()
    region.UpdatePropertyInformation()
    pivot = list(region.GetProperty('PivotInfo'))
    x, y = gui.screen_point(view, pivot)
    undo = gui.action('actionEditUndo')
    undo_before = undo.text()
    xinput.move(x, y)
    xinput.press(wait=ARRIVAL)
    xinput.move(x, y - 20, wait=ARRIVAL)
    xinput.release(wait=ARRIVAL)
    settle(seconds=1.0)
    check(list(region.Translation) == [0, 0, 0] and 'Move Handle' not in undo.text(),
          'a drag where the hidden handle box is moves nothing (Translation %s) and adds no undo step ("%s", before "%s")'
          % (list(region.Translation), undo.text(), undo_before))
    click(radios['Handle'])
    check(boxes() == (1, 0) and choice() == ['Handle'], 'Handle chosen again: %d handle, %d selection, choice %s'
          % (boxes() + (choice(),)))
    click(radios['None'])
    check(boxes() == (0, 0), 'None chosen: no box: %d handle, %d selection' % boxes())
    click(radios['Handle'])
    # the selection box's own Show check box: it becomes the one box
    show_selection = [b for b in window.findChildren(QCheckBox) if b.text() == 'Show Selection Box' and b.isVisible()][0]
    click(show_selection, left=8)
    check(boxes() == (0, 1) and choice() == ['Selection'], 'Show Selection Box ticked: the selection box alone and the choice '
          'says so: %d handle, %d selection, choice %s' % (boxes() + (choice(),)))
    click(show_selection, left=8)
    check(boxes() == (1, 0) and choice() == ['Handle'], 'Show Selection Box unticked: the handle box is back: %d handle, '
          '%d selection, choice %s' % (boxes() + (choice(),)))
    # another role: the selection box is the region's box
    region.Role = 'Fixed'
    region.UpdatePipeline()
    settle(seconds=1.0)
    check(boxes() == (0, 1), 'a Fixed region shows its selection box: %d handle, %d selection' % boxes())
    region.Role = 'Handle'
    region.UpdatePipeline()
    settle(seconds=1.0)
    check(boxes() == (1, 0), 'a Handle again: its handle box alone: %d handle, %d selection' % boxes())

    # the centre sphere: twice as large, of its own colour (the last of the box's actors)
    actors = vtkPropCollection()
    representation.GetActors(actors)
    spheres = [actors.GetItemAsObject(i) for i in range(actors.GetNumberOfItems())][-7:]

    def radius(actor):
        b = actor.GetMapper().GetInput().GetBounds()
        return (b[1] - b[0]) / 2
    ratio = radius(spheres[6]) / radius(spheres[0])
    check(abs(ratio - 2) < 0.01, 'the centre sphere is twice the face spheres\' size: %.3g' % ratio)
    colour = list(spheres[6].GetProperty().GetColor())
    check(all(max(abs(a - b) for a, b in zip(colour, role)) > 0.2 for role in ROLE_COLOURS),
          'the centre sphere\'s colour %s is none of the roles\' %s' % (colour, ROLE_COLOURS))
    box = representation.GetBounds()
    lengths = [box[2 * i + 1] - box[2 * i] for i in range(3)]
    check(min(lengths) >= LEAST_ASPECT * max(lengths) * (1 - 1e-9), 'the box is at least %g as thick as it is long: %s'
          % (LEAST_ASPECT, lengths))
    # seen along the box's z axis the top face sphere lies in front of the centre: a drag there
    # still moves the handle (the centre is picked first), in the view's plane, without scaling
    view.CameraPosition = [pivot[0], pivot[1], pivot[2] + 4 * height]
    view.CameraFocalPoint = pivot
    view.CameraViewUp = [0, 1, 0]
    pvs.Render(view)
    settle(seconds=0.5)
    x, y = gui.screen_point(view, pivot)
    xinput.move(x, y)
    xinput.press(wait=ARRIVAL)
    settle(seconds=0.3)
    for k in (1, 2, 3):
        xinput.move(x + 10 * k, y, wait=ARRIVAL)
        settle(seconds=0.3)
    xinput.release(wait=ARRIVAL)
    settle(seconds=1.0)
    # the box's motion in the panel's fields (Apply not pressed)
    moved, scale = [[region.GetProperty(name).SMProperty.GetUncheckedElement(i) for i in range(3)]
                    for name in ('Translation', 'Scale')]
    check(moved[0] > 0 and abs(moved[2]) < 1e-9 * height and scale == [1, 1, 1],
          'a drag from the centre, a face sphere in front of it, moves the handle in the view\'s plane: Translation %s, '
          'Scale %s' % (moved, scale))
    check('Move Handle' in undo.text(), 'the drag is an undo step: "%s"' % undo.text())
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], error)
