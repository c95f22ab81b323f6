"""Run inside the paraview GUI (paraview --script=test_gui.py): the plugin loads and its filters
sit in one menu category. Writes 'ok' or the failure to the file named by MLSDEFORM_GUI_RESULT."""
import os

from paraview.simple import LoadPlugin
from paraview import servermanager as sm

result = os.environ['MLSDEFORM_GUI_RESULT']
try:
    LoadPlugin(os.environ['MLSDEFORM_PLUGIN'], remote=False, ns=globals())
    categories = set()
    for name in ('MLSSampler', 'ConstraintRegion', 'MLSDeform'):
        hints = sm.ProxyManager().GetPrototypeProxy('filters', name).GetHints()
        menu = hints.FindNestedElementByName('ShowInMenu') if hints else None
        categories.add(menu.GetAttribute('category') if menu else None)
    message = 'ok' if categories == {'MLS Deformation'} else 'categories: %s' % categories
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    message = 'error: %s' % error
with open(result, 'w') as f:
    f.write(message)
