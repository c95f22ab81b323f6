"""Run inside the paraview GUI (paraview --dr --script=test_gui_save_data_default.py): issue 63,
point 2. File > Save Data of a deformation of what ParaView's CGNS reader read (cgns_source.py)
opens with the Mesh File Variant's file type preselected, so that OK writes the source's variant;
for data not read from a solver's file (a multiblock of a generated box, of the same data type)
the dialog preselects what it did before; and back on the deformation, the variant again.
Environment: MLSDEFORM_PLUGIN, MLSDEFORM_WORK (a folder for the CGNS file). Writes 'ok' or the
failures to MLSDEFORM_GUI_RESULT."""
import os

import checks  # Testing/Python, on PYTHONPATH
from checks import check, write_result

error = None
try:
    from PyQt5.QtCore import QTimer
    from PyQt5.QtWidgets import QApplication, QWidget
    import paraview.simple as pvs
    import cgns_source
    import gui

    pvs.LoadPlugin(os.environ['MLSDEFORM_PLUGIN'], remote=False, ns=globals())
    app = QApplication.instance()
    gui.activate()

    def settle(seconds=1.0):
        checks.settle(app, seconds=seconds)

    def preselected(source):
        """The file type File > Save Data preselects for source (the dialog then cancelled)."""
        pvs.SetActiveSource(source)
        settle()
        seen = []

        def look():
            dialog = QApplication.activeModalWidget()
            if dialog is None:
                QTimer.singleShot(100, look)
                return
            types = [w for w in dialog.findChildren(QWidget) if w.objectName() == 'EntityType']
            seen.append(types[0].currentText() if types else '(no file type box)')
            dialog.reject()
        QTimer.singleShot(200, look)
        gui.action('actionFileSaveData').trigger()  # returns once the dialog is closed
        settle(0.5)
        return seen[0] if seen else '(no dialog)'

    reader = pvs.CGNSSeriesReader(FileNames=[cgns_source.make(os.path.join(os.environ['MLSDEFORM_WORK'], 'source.cgns'))])
    fixed = ConstraintRegion(Input=reader, Role='Fixed')  # noqa: F821 (the plugin's)
    fixed.Region = 'Box'
    fixed.Region.Position, fixed.Region.Length = [-1, -1, -1], [10, 10, 1.5]
    handle = ConstraintRegion(Input=reader, Role='Handle', Translation=[0.2, 0.1, 0.3])  # noqa: F821
    handle.Region = 'Box'
    handle.Region.Position, handle.Region.Length = [-1, -1, 2.5], [10, 10, 10]
    deform = MLSDeform(Input=reader, Regions=[fixed, handle], NumberOfSamples=40)  # noqa: F821
    pvs.Show(deform)
    other = pvs.GroupDatasets(Input=[pvs.Tetrahedralize(Input=pvs.Wavelet(WholeExtent=[0, 4, 0, 4, 0, 4]))])
    pvs.Show(other)
    pvs.Render()
    settle()
    VARIANT = 'A variant of the source mesh file'
    baseline = preselected(other)
    check(not baseline.startswith(VARIANT), 'Save Data of a generated multiblock preselects ParaView\'s own: "%s"' % baseline)
    first = preselected(deform)
    check(first.startswith(VARIANT), 'Save Data of the deformation of a CGNS file preselects the variant: "%s"' % first)
    plain = preselected(other)
    check(plain == baseline, 'Save Data of the generated multiblock again preselects what it did: "%s"' % plain)
    again = preselected(deform)
    check(again.startswith(VARIANT), 'and of the deformation again the variant: "%s"' % again)
    # Edit > Settings > MLS Deform > Save Data Writes Variants off: ParaView's writers again
    settings = pvs.GetSettingsProxy('MLSDeformSettings')
    check(settings is not None, "the GUI has the plugin's settings (Edit > Settings > MLS Deform)")
    settings.SaveDataWritesVariants = 0
    off = preselected(deform)
    check(not off.startswith(VARIANT), 'with Save Data Writes Variants off, the variant is not offered: "%s"' % off)
    settings.SaveDataWritesVariants = 1
except Exception as e:  # the GUI swallows exceptions: reported in the result file
    error = e
write_result(os.environ['MLSDEFORM_GUI_RESULT'], error)
