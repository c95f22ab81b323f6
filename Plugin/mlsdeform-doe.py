"""Design of experiments on an OpenFOAM case from the command line (mlsdeform/cli.py):

    python3 mlsdeform-doe.py DESIGN.json FOLDER (--samples N [--seed S] | --table CSV) [options]

(or pvpython in place of python3; another python3 hands itself to one of those). It sits beside
the plugin, with the mlsdeform package and the plugin's Python wrapping, and imports them from
there; --help lists the options."""
import os
import runpy
import sys

here = os.path.dirname(os.path.abspath(__file__))

# A python3 without ParaView's VTK modules and numpy (pyenv's, conda's: first on many PATHs) hands
# the command to one that has them (mlsdeform/interpreter.py; VTK loads after the allocator's
# restart below).
runpy.run_path(os.path.join(here, 'mlsdeform', 'interpreter.py'))['handOver'](('numpy', 'vtkmodules'), __file__, 'mlsdeform-doe')
# glibc's allocator settings for a batch (mlsdeform/allocator.py): it restarts the process, so it
# runs before the package loads VTK
runpy.run_path(os.path.join(here, 'mlsdeform', 'allocator.py'))['restartWithBatchAllocator']()
sys.path.insert(0, here)
import mlsdeform.cli  # noqa: E402

sys.exit(mlsdeform.cli.main(sys.argv[1:]))
