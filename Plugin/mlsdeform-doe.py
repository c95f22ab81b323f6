"""Design of experiments on an OpenFOAM case from the command line (mlsdeform/cli.py):

    pvpython mlsdeform-doe.py DESIGN.json FOLDER (--samples N [--seed S] | --table CSV) [options]

It sits beside the plugin and loads it from there; --help lists the options."""
import os
import sys

from paraview.simple import LoadPlugin

LoadPlugin(os.path.join(os.path.dirname(os.path.abspath(__file__)), 'MLSDeform.so'), remote=False)
import mlsdeform.cli  # noqa: E402  (embedded in the plugin)

sys.exit(mlsdeform.cli.main(sys.argv[1:]))
