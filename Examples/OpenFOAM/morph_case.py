"""Morphs an OpenFOAM case into a variant case: pvpython morph_case.py PLUGIN CASE.foam VARIANT_FOLDER
[--handle PATCH ...] [--translate DX DY DZ] [--fixed PATCH ...] [--slip PATCH ...]
[--rigid-layers N] [--overwrite] [--check [ITERATIONS]].
Defaults fit Examples/OpenFOAM/sphereChannel (the sphere moved by 5 cm along x and 2 cm up).
--check runs OpenFOAM's checkMesh on the variant and then ITERATIONS (default 5) iterations of
simpleFoam, to show that the solver runs on it; the exit status is non-zero if either fails."""
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
parser.add_argument('--rigid-layers', type=int, default=0, help='keep the cells within N layers of the handle rigid')
parser.add_argument('--overwrite', action='store_true')
parser.add_argument('--check', type=int, nargs='?', const=5, default=0, metavar='ITERATIONS')
args = parser.parse_args()

LoadPlugin(args.plugin, remote=False)
import openfoam_variant  # noqa: E402

start = time.time()
reader = openfoam_variant.open_case(args.case, args.handle + args.fixed + args.slip)
deformed = openfoam_variant.morph(reader, args.handle, args.translate, args.fixed, args.slip, args.rigid_layers)
openfoam_variant.save_variant(deformed, os.path.join(args.variant, 'case.foam'), args.overwrite)
field = deformed.GetDataInformation().GetFieldDataInformation()
print('variant written to %s in %.1f s (set-up %.2f s, solve %.3f s, handle residual %.2g)' % (
    args.variant, time.time() - start, field.GetArrayInformation('SetupTime').GetComponentRange(0)[0],
    field.GetArrayInformation('SolveTime').GetComponentRange(0)[0],
    field.GetArrayInformation('HandleResidual').GetComponentRange(0)[0]))

if args.check:
    import subprocess
    openfoam = 'source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1; cd "%s" && ' % args.variant
    for name, command in (('checkMesh', 'checkMesh'),
                          ('simpleFoam', 'foamDictionary -entry endTime -set %d system/controlDict >/dev/null && '
                           'foamDictionary -entry writeInterval -set %d system/controlDict >/dev/null && simpleFoam' % (args.check, args.check))):
        run = subprocess.run(['bash', '-c', openfoam + command], capture_output=True, text=True)
        open(os.path.join(args.variant, 'log.' + name), 'w').write(run.stdout + run.stderr)
        lines = [l.strip() for l in run.stdout.splitlines() if l.strip()]
        summary = [l for l in lines if 'Mesh OK' in l or 'Failed' in l or 'non-orthogonality Max' in l] if name == 'checkMesh' else lines[-2:]
        print('%s: %s' % (name, ' | '.join(summary)))
        if run.returncode != 0 or (name == 'checkMesh' and 'Mesh OK.' not in run.stdout):
            sys.exit('%s failed on the variant (see %s)' % (name, os.path.join(args.variant, 'log.' + name)))
