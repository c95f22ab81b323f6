"""The README's picture of the GUI (Examples/gui_handle_box.png): the fandisk's handle dragged with
its box, the Constraint Region's panel showing the motion the box set. Run inside the GUI, from
the repository's root:

    xvfb-run -a -s "-screen 0 1600x1000x24" paraview --dr --script=Examples/gui_screenshot.py
        (environment: MLSDEFORM_PLUGIN, MLSDEFORM_DATA_DIR, MLSDEFORM_SCREENSHOT)

It builds the pipeline of Testing/Python/test_gui_handle_widget.py, moves the box as a drag does,
presses Apply, grabs the main window with PyQt5 and quits.
"""
import os
import runpy
import sys

from PyQt5.QtCore import Qt
from PyQt5.QtWidgets import QApplication, QDockWidget, QPushButton, QScrollArea, QWidget

os.environ['MLSDEFORM_GUI_RESULT'] = os.environ['MLSDEFORM_SCREENSHOT'] + '.result'
sys.path.insert(0, 'Examples')  # fandisk_scene
runpy.run_path(os.path.join('Testing', 'Python', 'test_gui_handle_widget.py'))
window = [w for w in QApplication.topLevelWidgets() if w.objectName() == 'pqClientMainWindow'][0]
window.resize(1400, 900)
window.resizeDocks([window.findChild(QDockWidget, 'propertiesDock')], [430], Qt.Horizontal)
window.findChild(QPushButton, 'Accept').click()
for _ in range(20):
    QApplication.processEvents()
# the panel scrolled to the Handle Motion fields
window.resizeDocks([window.findChild(QDockWidget, 'pipelineBrowserDock')], [190], Qt.Vertical)
field = [w for w in window.findChildren(QWidget, 'Translation_2') if w.isVisible()][0]
area = [a for a in window.findChildren(QScrollArea) if a.isVisible() and a.isAncestorOf(field)][-1]
area.ensureWidgetVisible(field, 50, 250)
for _ in range(20):
    QApplication.processEvents()
window.grab().save(os.environ['MLSDEFORM_SCREENSHOT'])
os.remove(os.environ['MLSDEFORM_GUI_RESULT'])
QApplication.quit()
