"""Design of experiments on an OpenFOAM case from the command line (mlsdeform/cli.py):

    python3 mlsdeform-doe.py DESIGN.json FOLDER (--samples N [--seed S] | --table CSV) [options]

(or pvpython in place of python3; another python3 hands itself to one of those). It sits beside
the plugin, with the mlsdeform package and the plugin's Python wrapping, and imports them from
there; --help lists the options."""
import importlib.util
import os
import runpy
import shutil
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))

# A python3 without ParaView's VTK modules and numpy (pyenv's, conda's: first on many PATHs) hands
# the command to one that has them: Debian's python3 (packages python3-paraview, python3-numpy)
# or pvpython; none found, it says which it needs. (Looked up, not imported: VTK loads after the
# allocator's restart below.)
NEEDED = ('numpy', 'vtkmodules')
missing = [name for name in NEEDED if importlib.util.find_spec(name) is None]
if missing:
    check = 'import importlib.util, sys; sys.exit(any(importlib.util.find_spec(m) is None for m in %r))' % (NEEDED,)
    for python in ('/usr/bin/python3', shutil.which('pvpython')):
        if python and subprocess.run([python, '-c', check], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0:
            os.execv(python, [python, os.path.abspath(__file__)] + sys.argv[1:])
    sys.exit(f"mlsdeform-doe: this Python ({sys.executable}) has no {' and no '.join(missing)}: run it with Debian's "
             f"python3 (packages python3-paraview and python3-numpy) or with pvpython")
# glibc's allocator settings for a batch (mlsdeform/allocator.py): it restarts the process, so it
# runs before the package loads VTK
runpy.run_path(os.path.join(here, 'mlsdeform', 'allocator.py'))['restartWithBatchAllocator']()
sys.path.insert(0, here)
import mlsdeform.cli  # noqa: E402

sys.exit(mlsdeform.cli.main(sys.argv[1:]))
