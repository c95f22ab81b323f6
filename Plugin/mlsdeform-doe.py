"""Design of experiments on an OpenFOAM case from the command line (mlsdeform/cli.py):

    python3 mlsdeform-doe.py DESIGN.json FOLDER (--samples N [--seed S] | --table CSV) [options]

(or pvpython in place of python3). It sits beside the plugin, with the mlsdeform package and the
plugin's Python wrapping, and imports them from there; --help lists the options."""
import os
import runpy
import sys

here = os.path.dirname(os.path.abspath(__file__))
# glibc's allocator settings for a batch (mlsdeform/allocator.py): it restarts the process, so it
# runs before the package loads VTK
runpy.run_path(os.path.join(here, 'mlsdeform', 'allocator.py'))['restartWithBatchAllocator']()
sys.path.insert(0, here)
import mlsdeform.cli  # noqa: E402

sys.exit(mlsdeform.cli.main(sys.argv[1:]))
