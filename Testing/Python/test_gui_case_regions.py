"""Run inside the paraview GUI (paraview --dr --script=test_gui_case_regions.py): issue 54, point 4.
The sphereChannel case's set-up as a user makes it with the X server's mouse (xinput: XTest): the
case opened with its patches; for each role, Filters > MLS Deformation > Constraint Region on the
case, whose panel shows the case's blocks to tick (SelectionMode Blocks from the start on a
composite input), the patches ticked, Apply. One region per role: Handle body; Fixed inlet and
outlet; Slip ground, top, front and back (each in its own plane). MLS Deform made as the README
says: the case selected, Filters > MLS Deform, its input dialog given the regions. The pipeline browser names each
region after its role and patches, a name the user gives stays, and MLS Deform over the three
deforms the case with the sphere moved and the slip patches in their planes. The window's
pictures go to MLSDEFORM_SCREENSHOT_DIR (the README's walk-through). Writes 'ok' or the failures
to MLSDEFORM_GUI_RESULT."""
import os

import checks  # Testing/Python, on PYTHONPATH
from checks import check, write_result

# Seconds for the X server's events to reach the application (Qt's xcb thread).
ARRIVAL = 0.05

try:
    from PyQt5.QtCore import Qt
    from PyQt5.QtWidgets import QAction, QApplication, QDockWidget, QPushButton, QTreeView, QWidget
    import paraview.simple as pvs
    from paraview import servermanager
    import fandisk_scene as scene  # Examples/, on PYTHONPATH
    import gui
    import xinput

    scene.load_plugin(os.environ['MLSDEFORM_PLUGIN'])
    app = QApplication.instance()
    window = gui.activate()
    window.resize(1400, 900)
    window.resizeDocks([window.findChild(QDockWidget, 'propertiesDock')], [430], Qt.Horizontal)
    pictures = os.environ.get('MLSDEFORM_SCREENSHOT_DIR')

    def settle(until=lambda: False, seconds=5.0):
        checks.settle(app, until, seconds)

    def click(widget, left=None):
        xinput.click(*gui.reveal(widget, left), wait=ARRIVAL)
        settle(seconds=0.5)

    def picture(name):
        if pictures:
            os.makedirs(pictures, exist_ok=True)
            settle(seconds=0.5)
            window.grab().save(os.path.join(pictures, name))

    reader = pvs.OpenFOAMReader(FileName=os.environ['MLSDEFORM_CASE'])
    reader.MeshRegions = reader.MeshRegions.Available  # the internal mesh and every patch, as ticked in its panel
    view = pvs.GetActiveViewOrCreate('RenderView')
    pvs.Show(reader, view)
    pvs.Hide(reader, view)
    apply = [b for b in window.findChildren(QPushButton) if b.objectName() == 'Accept'][0]

    def name_of(proxy):
        return {p: name for (name, _), p in pvs.GetSources().items()}[proxy]

    def header():
        return [w for w in window.findChildren(QWidget) if w.objectName() == 'PropertiesButton'][0].property('text')

    def region_for(role, patches):
        """Filters > Constraint Region on the case, the role chosen, the patches ticked, Apply."""
        region = gui.new_region(reader, settle)
        check(region.SelectionMode == 'Blocks', 'a new region on the case selects blocks from the start (%s)' % region.SelectionMode)
        check(name_of(region) == 'Handle' and header() == 'Properties (Handle)',
              'a new region is named by its (default) role from the start: "%s", the panel\'s header "%s" (issue 63)'
              % (name_of(region), header()))
        handles, shown = gui.shown_boxes(view)
        check(not shown, 'a new region shows no box before its first Apply (%d)' % len(shown))
        combo = gui.choose_role(window, role, click, settle, ARRIVAL)
        check(combo.currentText() == role, 'the Role chosen in the panel: %s' % combo.currentText())
        tree = [w for w in window.findChildren(QWidget) if w.metaObject().className() == 'pqDataAssemblyPropertyWidget'
                and w.isVisible()][0].findChildren(QTreeView)[0]
        model = tree.model()
        items = {}

        def collect(parent):
            for r in range(model.rowCount(parent)):
                index = model.index(r, 0, parent)
                items[model.data(index)] = index
                collect(index)
        collect(tree.rootIndex())
        for patch in patches:
            gui.tick(tree, items[patch], settle, ARRIVAL)
        click(apply)
        settle(lambda: region.GetDataInformation().GetNumberOfPoints() > 0)
        check(sorted(str(b).split('/')[-1] for b in region.Blocks) == sorted(patches),
              'the ticked patches are the region\'s Blocks: %s' % list(region.Blocks))
        settle(lambda: header() == 'Properties (%s)' % name_of(region), seconds=3)
        check(header() == 'Properties (%s)' % name_of(region) and name_of(region).startswith(role),
              'once applied the panel\'s header follows the region\'s name: "%s"' % header())
        return region

    handle = region_for('Handle', ['body'])
    fixed = region_for('Fixed', ['inlet', 'outlet'])
    slip = region_for('Slip', ['ground', 'top', 'front', 'back'])
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [2, -6, 4], [1.5, 0.5, 0.5], [0, 0, 1]
    view.ResetCamera()
    pvs.Render(view)
    picture('gui_case_regions.png')
    names = {proxy: name for (name, _), proxy in pvs.GetSources().items()}
    for region, name in ((handle, 'Handle: body'), (fixed, 'Fixed: inlet, outlet'), (slip, 'Slip: ground, top, front +1')):
        check(names[region] == name, 'the pipeline browser names the region "%s" (expected "%s")' % (names[region], name))
    points = {r: r.GetDataInformation().GetNumberOfPoints() for r in (handle, fixed, slip)}
    check(all(points.values()), 'each region selects its patches\' points: %s' % list(points.values()))

    # MLS Deform over the three, as the README says: the case selected, Filters > MLS Deform, and
    # in the dialog that opens the three regions chosen for the Regions port (a click on Regions,
    # then on the regions with Ctrl), OK, Apply
    from PyQt5.QtCore import QPoint, QTimer
    from PyQt5.QtWidgets import QRadioButton

    def dialog():
        return QApplication.activeModalWidget()

    def choose_regions():
        ports = [b for b in dialog().findChildren(QRadioButton) if b.text() == 'Regions']
        check(len(ports) == 1, 'the input dialog offers the Regions port')
        xinput.click(*xinput.centre(ports[0]), wait=ARRIVAL)

    def pick_regions():
        # the dialog's pipeline (ParaView's pqFlatTreeView, no Qt item view): the case, its three
        # regions, one row each of max(font height, indent) + 4 pixels, the indent the small icons'
        # size + 2, at least 18 (pqFlatTreeView's layout)
        from PyQt5.QtGui import QFontMetrics
        from PyQt5.QtWidgets import QHeaderView, QStyle
        view = [w for w in dialog().findChildren(QWidget) if w.objectName() == 'pipelineView'][0]
        indent = max(view.style().pixelMetric(QStyle.PM_SmallIconSize) + 2, 18)
        row = max(QFontMetrics(view.font()).height(), indent) + 4
        header = [h.height() for h in view.viewport().findChildren(QHeaderView) if h.isVisible()]
        top = header[0] if header else 0
        for k, line in enumerate((1, 2, 3)):
            at = view.viewport().mapToGlobal(QPoint(100, top + line * row + 4 + (row - 4) // 2))
            xinput.click(at.x(), at.y(), wait=ARRIVAL, modifiers=['Control_L'] if k else [])

    def accept():
        ok = [b for b in dialog().findChildren(QPushButton) if b.text().replace('&', '') == 'OK']
        xinput.click(*xinput.centre(ok[0]), wait=ARRIVAL)

    steps = [choose_regions, pick_regions, accept]

    def run(i=0):  # each step on a later pass of the dialog's event loop, once the last one's clicks arrived
        if i < len(steps) and dialog() is not None:
            try:
                steps[i]()
            except Exception as error:  # an exception in a Qt slot ends ParaView: the dialog is closed instead
                check(False, 'step %d in the input dialog: %r' % (i, error))
                dialog().reject()
                return
            QTimer.singleShot(500, lambda: run(i + 1))
    pvs.SetActiveSource(reader)
    settle(seconds=0.5)
    QTimer.singleShot(1000, run)
    [a for a in window.findChildren(QAction) if a.text() == 'MLS Deform'][0].trigger()  # returns once the dialog closed
    settle(seconds=0.5)
    click(apply)
    deformed = pvs.GetActiveSource()
    settle(lambda: deformed.GetDataInformation().GetNumberOfPoints() > 0, seconds=30)
    check(deformed.GetXMLName() == 'MLSDeform' and list(deformed.Input) == [reader] if hasattr(deformed.Input, '__len__')
          else deformed.Input == reader, 'the dialog made MLS Deform on the case')
    check(set(deformed.Regions) == {handle, fixed, slip}, 'with the three regions as its Regions (%d)' % len(deformed.Regions))
    pvs.Show(deformed, view)
    handle.Translation = [0.0, 0.0, 0.05]
    pvs.SetActiveSource(handle)
    pvs.Render(view)
    settle(seconds=1.0)
    error = deformed.GetDataInformation().GetFieldDataInformation().GetArrayInformation('DeformationError')
    check(error is None, 'MLS Deform over one region per role deforms the case (%s)' % (error.GetStringValue(0) if error else 'no error'))
    data = servermanager.Fetch(deformed)
    boundary = data.GetBlock(1)
    blocks = {boundary.GetMetaData(i).Get(boundary.NAME()): boundary.GetBlock(i) for i in range(boundary.GetNumberOfBlocks())}

    def moved(name, axis):
        d = blocks[name].GetPointData().GetArray('Displacement')
        return max(abs(d.GetComponent(i, axis)) for i in range(d.GetNumberOfTuples()))
    body_lift = min(blocks['body'].GetPointData().GetArray('Displacement').GetComponent(i, 2)
                    for i in range(blocks['body'].GetNumberOfPoints()))
    check(abs(body_lift - 0.05) <= 1e-6, 'the sphere moved up by 0.05 (its least lift %.6g)' % body_lift)
    # each slip patch stays in its plane (the normal component removed: round-off of float points)
    for name, axis in (('ground', 2), ('top', 2), ('front', 1), ('back', 1)):
        check(moved(name, axis) <= 1e-9, 'the %s patch stays in its plane (normal displacement %.3g)' % (name, moved(name, axis)))
    # the README's picture: a slice of the deformed mesh through the sphere, coloured by the
    # displacement, the sphere's patch, and the handle's box
    for region in (fixed, slip):
        pvs.Hide(region, view)
    pvs.Hide(deformed, view)
    bounds = blocks['body'].GetBounds()
    centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
    cut = pvs.Slice(Input=deformed)
    cut.SliceType.Origin, cut.SliceType.Normal = centre, [0, 1, 0]
    shown = pvs.Show(cut, view)
    pvs.ColorBy(shown, ('POINTS', 'Displacement', 'Magnitude'))
    shown.SetScalarBarVisibility(view, True)
    sphere = pvs.ExtractBlock(Input=deformed, Selectors=['/Root/boundary/body'])
    pvs.Show(sphere, view)
    size = bounds[1] - bounds[0]  # the sphere's diameter: the view spans about six of them
    view.CameraPosition = [centre[0] + 1.5 * size, centre[1] - 8 * size, centre[2] + 2 * size]
    view.CameraFocalPoint = centre
    view.CameraViewUp = [0, 0, 1]
    pvs.SetActiveSource(handle)
    pvs.Render(view)
    picture('gui_case_deformed.png')

    # the user's own name stays when the selection changes
    pvs.RenameSource('sphere', handle)
    handle.Blocks = list(handle.Blocks) + ['/Root/boundary/top']
    handle.UpdatePipeline()
    settle(seconds=0.5)
    names = {proxy: name for (name, _), proxy in pvs.GetSources().items()}
    check(names[handle] == 'sphere', 'a name the user gave stays: "%s"' % names[handle])
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], error)
