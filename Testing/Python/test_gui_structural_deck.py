"""Issue 55, point 8: the structural loop in the GUI. Two runs on the plate deck of
Examples/Structural/plate.py (made by the pvpython run first):

    pvpython test_gui_structural_deck.py PLUGIN WORK make
        meshes the plate (Gmsh, C3D10) and writes the deck WORK/source/plate.inp.
    paraview --dr --script=test_gui_structural_deck.py --test-script=structural_deck.xml --exit
        (environment: MLSDEFORM_PLUGIN, MLSDEFORM_DECK, MLSDEFORM_GUI_RESULT; the X server's mouse:
        xinput, XTest) opens the deck as File > Open does (the Mesh File reader, not AVS UCD); for
        each role, Filters > MLS Deformation > Constraint Region on it, whose panel lists the
        deck's sets to tick (mode Blocks from the start), the role chosen, the sets ticked with
        the mouse, Apply: Fixed on fixed and load, Handle on hole1 moved along x; MLS Deform over
        both, made active. The recorded events then choose File > Save Data, the variant's .inp
        in the file dialog and OK in the writer's settings dialog.
    pvpython test_gui_structural_deck.py PLUGIN WORK check
        checks what the GUI wrote: its checks passed, the variant deck is the source with only the
        node coordinates changed (the included mesh beside it) and ccx runs on it.
"""
import os
import sys

in_gui = 'MLSDEFORM_DECK' in os.environ


def gui():
    import checks
    from checks import check
    from PyQt5.QtCore import Qt
    from PyQt5.QtWidgets import QApplication, QDockWidget, QPushButton, QTreeView, QWidget
    import paraview.simple as pvs
    import gui
    import xinput
    ARRIVAL = 0.05  # seconds for the X server's events to reach the application

    pvs.LoadPlugin(os.environ['MLSDEFORM_PLUGIN'], remote=False)
    app = QApplication.instance()
    window = gui.activate()
    window.resize(1400, 900)
    window.resizeDocks([window.findChild(QDockWidget, 'propertiesDock')], [430], Qt.Horizontal)

    def settle(until=lambda: False, seconds=5.0):
        checks.settle(app, until, seconds)

    def click(widget, left=None):
        xinput.click(*gui.reveal(widget, left), wait=ARRIVAL)
        settle(seconds=0.5)

    reader = pvs.OpenDataFile(os.environ['MLSDEFORM_DECK'])  # File > Open's choice of reader
    check(reader.GetXMLName() == 'MeshFileReader', 'the deck opens with the Mesh File reader (%s)' % reader.GetXMLName())
    view = pvs.GetActiveViewOrCreate('RenderView')
    shown = pvs.Show(reader, view)
    pvs.Render(view)
    # issue 63: the colouring menu lists the deck's fields and sets, not the arrays ParaView draws
    # quadratic elements with (vtkEdgeFlags) nor the reader's reports
    domain = shown.GetProperty('ColorArrayName').SMProperty.GetDomain('array_list')
    listed = [domain.GetString(i) for i in range(domain.GetNumberOfStrings())]
    check('hole1' in listed and not {'vtkEdgeFlags', 'SourceFile', 'QualityVerdict'} & set(listed),
          'the colouring menu of the deck lists %s' % listed)
    apply = [b for b in window.findChildren(QPushButton) if b.objectName() == 'Accept'][0]

    def region_for(role, sets):
        """Filters > Constraint Region on the deck, the role chosen, the sets ticked, Apply."""
        region = gui.new_region(reader, settle)
        check(region.SelectionMode == 'Blocks', 'a new region on a deck selects by name from the start (%s)' % region.SelectionMode)
        combo = gui.choose_role(window, role, click, settle, ARRIVAL)
        check(combo.currentText() == role, 'the Role chosen in the panel: %s' % combo.currentText())
        lists = [w for w in window.findChildren(QTreeView) if w.metaObject().className() == 'pqArraySelectionWidget'
                 and w.isVisible()]
        check(len(lists) == 1, 'the panel shows one list of sets (%d)' % len(lists))
        blocks = [w for w in window.findChildren(QWidget) if w.metaObject().className() == 'pqDataAssemblyPropertyWidget'
                  and w.isVisible()]
        check(not blocks, "a deck's region shows no (empty) Blocks box (%d shown; issue 63)" % len(blocks))
        tree = lists[0]
        model = tree.model()
        items = {model.data(model.index(r, 0)): model.index(r, 0) for r in range(model.rowCount())}
        check({'fixed', 'load', 'hole1', 'hole2'} <= set(items) and 'NodeId' not in items,
              'the list holds the deck\'s sets by name: %s' % sorted(items))
        for name in sets:
            gui.tick(tree, items[name], settle, ARRIVAL)
        if role == 'Handle':
            region.Translation = [0.4, 0, 0]  # typed in the panel's Translation (the handle's drag is tested elsewhere)
        click(apply)
        settle(lambda: region.GetDataInformation().GetNumberOfPoints() > 0)
        check(sorted(region.Sets) == sorted(sets), 'the ticked sets are the region\'s Sets: %s' % list(region.Sets))
        return region

    fixed = region_for('Fixed', ['fixed', 'load'])
    hole = region_for('Handle', ['hole1'])
    names = {proxy: name for (name, _), proxy in pvs.GetSources().items()}
    check(names[fixed] == 'Fixed: fixed, load' and names[hole] == 'Handle: hole1',
          'the pipeline browser names the regions after their sets: %s, %s' % (names[fixed], names[hole]))
    check(fixed.GetDataInformation().GetNumberOfPoints() == 166 and hole.GetDataInformation().GetNumberOfPoints() > 0,
          'the regions hold their sets\' nodes (%d, %d)' % (fixed.GetDataInformation().GetNumberOfPoints(),
                                                          hole.GetDataInformation().GetNumberOfPoints()))
    deform = pvs.MLSDeform(Input=reader, Regions=[fixed, hole])
    pvs.Show(deform, view)
    pvs.Render(view)
    data = deform.GetDataInformation().DataInformation
    check(data.GetNumberOfPoints() == reader.GetDataInformation().GetNumberOfPoints(), 'MLS Deform deforms the whole deck')
    pvs.SetActiveSource(deform)
    settle(seconds=0.5)


if in_gui:
    from checks import write_result
    try:
        gui()
        write_result(os.environ['MLSDEFORM_GUI_RESULT'])
    except Exception as e:  # the GUI swallows exceptions: the result file says it
        import traceback
        write_result(os.environ['MLSDEFORM_GUI_RESULT'], '%s\n%s' % (e, traceback.format_exc()))
else:
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(here)), 'Examples', 'Structural'))
    import plate
    from checks import check, finish
    plugin, work, step = sys.argv[1:4]
    source = os.path.join(work, 'source')
    if step == 'make':
        plate.mesh_plate(source, holes=((3.0, 2.0, 0.8), (7.0, 2.0, 0.8)), size=0.6)
        plate.write_analysis(source)
        sys.exit(0)
    result = open(os.path.join(work, 'result.txt')).read().strip()
    check(result == 'ok', 'the GUI\'s checks: %s' % result)
    variant = os.path.join(work, 'gui-variant', 'plate.inp')
    check(os.path.exists(variant) and open(variant, 'rb').read() == open(os.path.join(source, 'plate.inp'), 'rb').read(),
          'Save Data wrote the variant\'s main deck, byte for byte the source\'s')
    mesh, original = os.path.join(work, 'gui-variant', 'mesh.inp'), os.path.join(source, 'mesh.inp')
    if os.path.exists(mesh):
        a, b = open(original).read().split('*NODE\n', 1), open(mesh).read().split('*NODE\n', 1)
        nodes_a, rest_a = a[1].split('*', 1)
        nodes_b, rest_b = b[1].split('*', 1)
        ids = lambda text: [line.split(',')[0] for line in text.splitlines()]  # noqa: E731
        check(a[0] == b[0] and rest_a == rest_b and ids(nodes_a) == ids(nodes_b) and nodes_a != nodes_b,
              'the included mesh: the same node ids, moved coordinates, every other line as it was')
        displacement = plate.run_ccx(variant)
        check(len(displacement) > 0, 'ccx runs on the GUI\'s variant (%d load nodes)' % len(displacement))
    else:
        check(False, 'Save Data wrote the included mesh beside the deck')
    finish()
