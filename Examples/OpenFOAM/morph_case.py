"""Morphs an OpenFOAM case into a variant case: pvpython morph_case.py PLUGIN CASE.foam VARIANT_FOLDER
[--handle PATCH ...] [--translate DX DY DZ] [--fixed PATCH ...] [--slip PATCH ...] [--overwrite].
Defaults fit Examples/OpenFOAM/sphereChannel (the sphere moved by 5 cm along x and 2 cm up)."""
import argparse
import os
import sys
import time

from paraview.simple import LoadPlugin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument('plugin')
parser.add_argument('case')
parser.add_argument('variant')
parser.add_argument('--handle', nargs='+', default=['body'])
parser.add_argument('--translate', nargs=3, type=float, default=[0.05, 0.0, 0.02])
parser.add_argument('--fixed', nargs='*', default=['inlet', 'outlet'])
parser.add_argument('--slip', nargs='*', default=['ground', 'top', 'front', 'back'])
parser.add_argument('--overwrite', action='store_true')
args = parser.parse_args()

LoadPlugin(args.plugin, remote=False)
import openfoam_variant  # noqa: E402

start = time.time()
reader = openfoam_variant.open_case(args.case, args.handle + args.fixed + args.slip)
deformed = openfoam_variant.morph(reader, args.handle, args.translate, args.fixed, args.slip)
openfoam_variant.save_variant(deformed, os.path.join(args.variant, 'case.foam'), args.overwrite)
field = deformed.GetDataInformation().GetFieldDataInformation()
print('variant written to %s in %.1f s (set-up %.2f s, solve %.3f s, handle residual %.2g)' % (
    args.variant, time.time() - start, field.GetArrayInformation('SetupTime').GetComponentRange(0)[0],
    field.GetArrayInformation('SolveTime').GetComponentRange(0)[0],
    field.GetArrayInformation('HandleResidual').GetComponentRange(0)[0]))
