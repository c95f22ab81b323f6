"""What the GUI tests (scripts run inside the paraview GUI) look up in ParaView's window: its
actions, the render view's widget, the boxes shown in a view, a point's place on the screen."""
from PyQt5.QtCore import QPoint
from PyQt5.QtWidgets import QAction, QApplication, QWidget


def main_window():
    return [w for w in QApplication.instance().topLevelWidgets() if w.objectName() == 'pqClientMainWindow'][0]


def action(name):
    """A main window action by its object name ('actionEditUndo')."""
    actions = [a for a in main_window().findChildren(QAction) if a.objectName() == name]
    if not actions:
        raise RuntimeError('no action %s in the main window' % name)
    return actions[0]


def widget(class_name, object_name=None):
    """The main window's first widget of a Qt class (and object name)."""
    found = [w for w in main_window().findChildren(QWidget) if w.metaObject().className() == class_name
             and (object_name is None or w.objectName() == object_name)]
    if not found:
        raise RuntimeError('no %s%s in the main window' % (class_name, ' ' + object_name if object_name else ''))
    return found[0]


def shown_boxes(view):
    """The box widgets shown in a render view: (the handle boxes, every box)."""
    shown = [p.SMProxy for p in view.GetProperty('HiddenRepresentations')
             if p.SMProxy.GetXMLName().endswith('BoxWidgetRepresentation') and p.SMProxy.GetProperty('Visibility').GetElement(0)]
    return [b for b in shown if (b.GetLogName() or '').startswith('handle motion box of ')], shown


def screen_point(view, world):
    """The global screen position (pixels, as the pointer's) of a world point in a render view."""
    renderer = view.GetRenderer()
    renderer.SetWorldPoint(list(world) + [1.0])
    renderer.WorldToDisplay()
    x, y = renderer.GetDisplayPoint()[:2]
    canvas = widget('pqQVTKWidget')
    ratio = canvas.devicePixelRatioF()
    top_left = canvas.mapToGlobal(QPoint(0, 0))
    return top_left.x() + x / ratio, top_left.y() + canvas.height() - y / ratio


def activate():
    """The main window active (there is no window manager under Xvfb to do it on a click)."""
    window = main_window()
    window.activateWindow()
    window.raise_()
    return window


def reveal(child, left=None, point=None):
    """Scrolls the scroll area that holds a widget (the Properties panel) until it shows the
    widget's centre, the point `left` pixels from its left edge (a check box's box: a stretched
    check box takes no click right of its text), or a QPoint of the widget (an item of a list), and
    returns that point's global position."""
    from PyQt5.QtWidgets import QScrollArea
    if point is None:
        point = child.rect().center()
        if left is not None:
            point.setX(left)
    parent = child.parentWidget()
    while parent is not None and not isinstance(parent, QScrollArea):
        parent = parent.parentWidget()
    if parent is not None and parent.widget() is not None:
        inside = child.mapTo(parent.widget(), point)
        parent.ensureVisible(inside.x(), inside.y(), 20, 20)
    QApplication.instance().processEvents()
    point = child.mapToGlobal(point)
    return point.x(), point.y()


class FandiskHandle:
    """The fandisk of Examples/fandisk_scene.py (bottom 10% Fixed, top 25% the Handle, unmoved),
    deformed with 300 samples and shown with its regions, the Handle active; its handle box alone
    in the view (box, and its representation)."""

    def __init__(self, scene):
        import os
        import paraview.simple as pvs
        from checks import settle
        self.part = pvs.OpenDataFile(os.path.join(os.environ['MLSDEFORM_DATA_DIR'], 'fandisk.off'))
        self.part.UpdatePipeline()
        self.bounds = self.part.GetDataInformation().GetBounds()
        self.height = self.bounds[5] - self.bounds[4]
        self.fixed, self.handle = scene.fixed_and_handle(self.part, self.bounds)
        self.handle.Translation = [0, 0, 0]
        self.deformed = scene.MLSDeform(Input=self.part, Regions=[self.fixed, self.handle], NumberOfSamples=300)
        self.view = pvs.GetActiveViewOrCreate('RenderView')
        for source in (self.deformed, self.fixed, self.handle):
            pvs.Show(source, self.view)
        pvs.SetActiveSource(self.handle)
        pvs.Render(self.view)
        settle(QApplication.instance(), seconds=0.5)
        boxes, shown = shown_boxes(self.view)
        if len(boxes) != 1 or len(shown) != 1:
            raise RuntimeError('expected the handle box alone, found %d handle boxes of %d boxes' % (len(boxes), len(shown)))
        self.box = boxes[0]
        self.representation = self.box.GetRepresentationProxy().GetClientSideObject()

    def oblique(self):
        """The camera from the side and above: no face sphere in front of the box's centre."""
        import paraview.simple as pvs
        self.view.CameraPosition = [1.5 * self.height, -3 * self.height, 1.2 * self.height]
        self.view.CameraFocalPoint = [0, 0, 0]
        self.view.CameraViewUp = [0, 0, 1]
        self.view.ResetCamera()
        pvs.Render(self.view)


def new_region(source, settle):
    """Filters > MLS Deformation > Constraint Region on source, as a user makes it: returns the new
    region (the active source)."""
    import paraview.simple as pvs
    pvs.SetActiveSource(source)
    settle(seconds=0.5)
    [a for a in main_window().findChildren(QAction) if a.text() == 'Constraint Region'][0].trigger()
    settle(seconds=1.0)
    return pvs.GetActiveSource()


def choose_role(window, role, click, settle, wait):
    """Chooses role in the visible Constraint Region panel's Role combo box as a user does: a click
    on it, the arrow keys, Return (the X server's: xinput). Returns the combo box."""
    from PyQt5.QtWidgets import QComboBox
    import xinput
    combo = [c for c in window.findChildren(QComboBox) if c.isVisible() and c.findText('Slip') >= 0 and c.findText('Handle') >= 0][0]
    if combo.currentText() != role:
        click(combo)
        for _ in range(abs(combo.findText(role) - combo.currentIndex())):
            xinput.key('Down' if combo.findText(role) > combo.currentIndex() else 'Up')
        xinput.key('Return', wait=wait)
        settle(seconds=0.5)
    return combo


def tick(tree, index, settle, wait):
    """Clicks the check box of a tree view's item (the X server's mouse)."""
    import xinput
    rect = tree.visualRect(index)
    rect.setLeft(rect.left() + 10)  # the item's check box
    xinput.click(*reveal(tree.viewport(), point=rect.topLeft() + (rect.bottomLeft() - rect.topLeft()) / 2), wait=wait)
    settle(seconds=0.3)
