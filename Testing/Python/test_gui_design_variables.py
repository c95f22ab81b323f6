"""Design variables in the GUI: a designer adds them to a Handle region in its Properties panel,
ticks MLS Deform's ComputeSensitivities and sees the model coloured by |dX/dp|; a state file keeps
them. Run inside the paraview GUI:

    paraview --dr --script=test_gui_design_variables.py --test-script=design_variables.xml --exit
        (environment: MLSDEFORM_PLUGIN, MLSDEFORM_DATA_DIR, MLSDEFORM_GUI_RESULT,
        MLSDEFORM_SCREENSHOT, MLSDEFORM_STATE; Examples/ on PYTHONPATH)

This script builds the fandisk pipeline of Examples/fandisk_scene.py (bottom 10% Fixed, top 25%
the Handle) with the Handle region active, and adds two actions to the main window that the
recorded events trigger to check what they did. The recorded events (design_variables.xml.in), as
the designer does them: in the Handle's Design Variables table Add three rows, name the first
'lift' and give it the value 0.02, make the second (p2) a Rotate, select the third and Remove it,
Apply; select MLS Deform, tick ComputeSensitivities, Apply; colour by dX/dlift (Magnitude);
select the Handle again and trigger checkColouring; File > Save State; Edit > Reset Session;
File > Load State; select the Handle and trigger checkRestored, which writes 'ok' or the failures
to MLSDEFORM_GUI_RESULT (the GUI swallows exceptions and exit codes). checkColouring also saves
the main window as MLSDEFORM_SCREENSHOT (ctest writes it in its build folder; the README's picture
Examples/gui_design_variables.png is a copy).
"""
import math
import os

import numpy
import paraview.simple as pvs
from paraview import servermanager
from paraview.vtk.util.numpy_support import vtk_to_numpy
from PyQt5.QtCore import Qt
from PyQt5.QtWidgets import QAction, QApplication, QComboBox, QDockWidget, QScrollArea, QTableWidget, QWidget

import fandisk_scene as scene  # Examples/, on PYTHONPATH

scene.load_plugin(os.environ['MLSDEFORM_PLUGIN'])

# The rows the recorded events type, as the property holds them and as the table shows them.
EXPECTED = ['lift', '0', '0', '0', '1', '0.02', '-1', '1',
            'p2', '1', '0', '0', '1', '0', '-1', '1']
SHOWN = [['lift', 'Translate', '0', '0', '1', '0.02', '-1', '1'],
         ['p2', 'Rotate', '0', '0', '1', '0', '-1', '1']]
# The sensitivities of the two variables (Examples/fandisk_scene.py's Handle at FixWeight's
# default, measured 0.26% and 0.2% off on the handle, 0.0017 on the fixed part): dX/dlift is the
# unit z axis on the handle within 1%, dX/dp2 is (pi/180) z x (x - pivot) there within 1% of its
# largest magnitude, and on the fixed part both stay below 1% of their size on the handle.
RELATIVE_TOLERANCE = 0.01

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def fandisk_pipeline():
    part = pvs.OpenDataFile(os.path.join(os.environ['MLSDEFORM_DATA_DIR'], 'fandisk.off'))
    part.UpdatePipeline()
    bounds = part.GetDataInformation().GetBounds()
    fixed, handle = scene.fixed_and_handle(part, bounds)
    deformed = scene.MLSDeform(Input=part, Regions=[fixed, handle])
    view = pvs.GetActiveViewOrCreate('RenderView')
    pvs.Show(deformed, view)
    view.CameraPosition = [0, -3, 1.5]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    pvs.SetActiveSource(handle)
    return bounds, handle


BOUNDS, HANDLE = fandisk_pipeline()
WINDOW = [w for w in QApplication.topLevelWidgets() if w.objectName() == 'pqClientMainWindow'][0]


def sources(xml_name):
    return [s for s in pvs.GetSources().values() if s.GetXMLName() == xml_name]


def shown_rows():
    """The visible Design Variables table's rows as the designer reads them (the kind: its combo box)."""
    tables = [w.findChild(QTableWidget, 'Table') for w in WINDOW.findChildren(QWidget, 'DesignVariables')
              if w.isVisible()]
    if len(tables) != 1:
        return 'expected one visible Design Variables table, found %d' % len(tables)
    table = tables[0]

    def cell(row, column):
        kind = table.cellWidget(row, column)
        return kind.currentText() if kind is not None else table.item(row, column).text()
    return [[cell(r, c) for c in range(table.columnCount())] for r in range(table.rowCount())]


def check_handle(what):
    """The active source is a Handle region holding the expected variables, shown in its table."""
    handle = pvs.GetActiveSource()
    check(handle is not None and handle.GetXMLName() == 'ConstraintRegion' and handle.Role == 'Handle',
          '%s: the active source is not the Handle region' % what)
    if handle is None or handle.GetXMLName() != 'ConstraintRegion':
        return None
    check(list(handle.DesignVariables) == EXPECTED, '%s: DesignVariables %s' % (what, list(handle.DesignVariables)))
    check(shown_rows() == SHOWN, '%s: the table shows %s' % (what, shown_rows()))
    return handle


def check_sensitivities(what):
    """MLS Deform outputs dX/dlift and dX/dp2 as designed. Returns |dX/dlift|'s range."""
    deformed = sources('MLSDeform')
    check(len(deformed) == 1, '%s: %d MLS Deform filters' % (what, len(deformed)))
    if len(deformed) != 1:
        return None
    deformed = deformed[0]
    check(deformed.ComputeSensitivities == 1, '%s: ComputeSensitivities is off' % what)
    output = servermanager.Fetch(deformed)
    arrays = {name: output.GetPointData().GetArray(name) for name in ('dX/dlift', 'dX/dp2')}
    check(all(a is not None and a.GetNumberOfComponents() == 3 for a in arrays.values()),
          '%s: no 3-component dX/dlift and dX/dp2 in %s' % (what, [output.GetPointData().GetArrayName(i)
                                                                for i in range(output.GetPointData().GetNumberOfArrays())]))
    if not all(arrays.values()):
        return None
    # the rest positions (the reader of the pipeline before a reset is gone)
    rest = vtk_to_numpy(output.GetPoints().GetData()) - vtk_to_numpy(output.GetPointData().GetArray('Displacement'))
    zmin, zmax = BOUNDS[4], BOUNDS[5]
    on_handle = rest[:, 2] >= zmax - 0.25 * (zmax - zmin)
    on_fixed = rest[:, 2] <= zmin + 0.1 * (zmax - zmin)
    lift = numpy.linalg.norm(vtk_to_numpy(arrays['dX/dlift']), axis=1)
    check(numpy.abs(lift[on_handle] - 1).max() <= RELATIVE_TOLERANCE,
          '%s: |dX/dlift| on the handle is %g-%g, not 1' % (what, lift[on_handle].min(), lift[on_handle].max()))
    check(lift[on_fixed].max() <= RELATIVE_TOLERANCE, '%s: |dX/dlift| on the fixed part up to %g' % (what, lift[on_fixed].max()))
    handle = [s for s in sources('ConstraintRegion') if s.Role == 'Handle'][0]
    handle.UpdatePropertyInformation()
    pivot = numpy.array(list(handle.GetProperty('PivotInfo')))
    turn = vtk_to_numpy(arrays['dX/dp2'])
    expected = math.pi / 180 * numpy.cross([0, 0, 1], rest - pivot)  # 1 degree about z per unit
    largest = numpy.linalg.norm(expected[on_handle], axis=1).max()
    error = numpy.linalg.norm(turn - expected, axis=1)[on_handle].max()
    check(error <= RELATIVE_TOLERANCE * largest, '%s: dX/dp2 on the handle is off a rotation about z by %g (of %g)'
          % (what, error, largest))
    check(numpy.linalg.norm(turn, axis=1)[on_fixed].max() <= RELATIVE_TOLERANCE * largest,
          '%s: |dX/dp2| on the fixed part up to %g' % (what, numpy.linalg.norm(turn, axis=1)[on_fixed].max()))
    return deformed, (lift.min(), lift.max())


def check_colouring(what, deformed, magnitudes):
    """The model is coloured by |dX/dlift| over its range, with its colour legend shown."""
    view = pvs.GetActiveView()
    look = pvs.GetDisplayProperties(deformed, view)
    check(list(look.ColorArrayName) == ['POINTS', 'dX/dlift'], '%s: coloured by %s' % (what, list(look.ColorArrayName)))
    colours = pvs.GetColorTransferFunction('dX/dlift')
    check(colours.VectorMode == 'Magnitude', '%s: the colour map shows the %s' % (what, colours.VectorMode))
    low, high = colours.RGBPoints[0], colours.RGBPoints[-4]
    # the map spans the data's range (ParaView rescales it to the data on colouring), exactly up to
    # the range's float round trip
    check(high > 0 and abs(low - magnitudes[0]) <= 1e-6 and abs(high - magnitudes[1]) <= 1e-6,
          '%s: the colour map spans %g-%g, |dX/dlift| %g-%g' % (what, low, high, magnitudes[0], magnitudes[1]))
    check(pvs.GetScalarBar(colours, view).Visibility == 1, '%s: no colour legend' % what)


def save_screenshot():
    """The main window as the README shows it: the Handle's table, the model coloured by |dX/dlift|."""
    WINDOW.resize(1400, 900)
    WINDOW.resizeDocks([WINDOW.findChild(QDockWidget, 'propertiesDock')], [470], Qt.Horizontal)
    table = [w for w in WINDOW.findChildren(QWidget, 'DesignVariables') if w.isVisible()][0]
    area = [a for a in WINDOW.findChildren(QScrollArea) if a.isVisible() and a.isAncestorOf(table)][-1]
    area.ensureWidgetVisible(table, 50, 100)
    for _ in range(20):
        QApplication.processEvents()
    pvs.Render()
    WINDOW.grab().save(os.environ['MLSDEFORM_SCREENSHOT'])


def guarded(what, steps):
    try:
        steps()
    except Exception as error:  # reported through the result file, the GUI swallows exceptions
        import traceback
        failures.append('%s: error %r\n%s' % (what, error, traceback.format_exc()))


def check_applied():
    handle = check_handle('after Apply')
    check(handle is not None and handle.SMProxy is HANDLE.SMProxy, 'after Apply: not the script\'s Handle')
    found = check_sensitivities('after Apply')
    if found:
        check_colouring('after Apply', *found)
    save_screenshot()


def check_restored():
    handle = check_handle('after Load State')
    check(handle is not None and handle.SMProxy is not HANDLE.SMProxy, 'after Load State: still the Handle before the reset')
    found = check_sensitivities('after Load State')
    if found:
        check_colouring('after Load State', *found)
    check(os.path.isfile(os.environ['MLSDEFORM_STATE']), 'no state file %s' % os.environ['MLSDEFORM_STATE'])


def report(*_):  # (triggered's checked argument)
    guarded('after Load State', check_restored)
    with open(os.environ['MLSDEFORM_GUI_RESULT'], 'w') as f:
        f.write('\n'.join(failures) or 'ok')
        f.write('\n')


# the recorded events trigger these (pqClientMainWindow/checkColouring, .../checkRestored)
for name, slot in (('checkColouring', lambda *_: guarded('after Apply', check_applied)), ('checkRestored', report)):
    action = QAction(name, WINDOW)
    action.setObjectName(name)
    action.triggered.connect(slot)
