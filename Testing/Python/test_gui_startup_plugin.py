"""Run inside the paraview GUI started with the plugin on its command line (README, 'Using the
plugin'): paraview --dr --plugin-search-paths=FOLDER --plugins=MLSDeform --script=this. The
script loads nothing itself: the plugin's filters exist only if the start-up options loaded it
(--dr keeps the user's Auto Load settings out). Writes 'ok' or the failure to the file named by
MLSDEFORM_GUI_RESULT."""
import os

from paraview import servermanager as sm

result = os.environ['MLSDEFORM_GUI_RESULT']
try:
    loaded = sm.ProxyManager().GetPrototypeProxy('filters', 'MLSDeform') is not None
    message = 'ok' if loaded else 'the plugin was not loaded at start-up'
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    message = 'error: %s' % error
with open(result, 'w') as f:
    f.write(message)
