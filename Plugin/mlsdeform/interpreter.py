"""The hand-over of a command to a Python that has the modules it needs.

The python3 first on many PATHs is not Debian's (pyenv's, conda's) and has neither numpy nor
ParaView's VTK modules. A script that needs them calls handOver(...) first: in a Python that
lacks one of them it executes the same command in Debian's python3 (packages python3-paraview,
python3-numpy, python3-scipy) or in pvpython, whichever has them all; none found, it exits
saying what it needs. (The modules are looked up, not imported.)

This module imports nothing of the package (whose import needs numpy), so that a script runs it
by its path first (runpy.run_path), as mlsdeform-doe.py and Examples/Structural/optimize_plate.py do.
"""
import importlib.util
import os
import shutil
import subprocess
import sys


def handOver(needed, script, who):
    """Returns in a Python that has every module of needed; otherwise runs script with this
    process's arguments in one that has them (this process ends there), or exits naming them."""
    missing = [name for name in needed if importlib.util.find_spec(name) is None]
    if not missing:
        return
    check = 'import importlib.util, sys; sys.exit(any(importlib.util.find_spec(m) is None for m in %r))' % (tuple(needed),)
    for python in ('/usr/bin/python3', shutil.which('pvpython')):
        if python and subprocess.run([python, '-c', check], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode == 0:
            sys.stdout.flush()
            os.execv(python, [python, os.path.abspath(script)] + sys.argv[1:])
    sys.exit(f"{who}: this Python ({sys.executable}) has no {' and no '.join(missing)}: run it with Debian's python3 "
             f"(packages python3-paraview, python3-numpy and python3-scipy) or with pvpython")
