"""OpenFOAM's adjoint chained through MLS Deform's design sensitivities, against finite differences
of the primal solver: dJ/dp = sum_i dJ/dX_i . dX_i/dp (adjointOptimisationFoam's surface
sensitivity read by mlsdeform.readFoamSensitivity, then DesignVariables.totalSensitivity) beside
(J(p + h) - J(p - h)) / 2h, each J from the primal solver on a variant case that MLS Deform wrote,
for the design variables of naca0012.py (angle of attack and thickness of the tutorial's NACA 0012).

Usage: pvpython validate_naca0012_adjoint.py PLUGIN WORK [--primal N] [--adjoint N] [--fd-primal N]
       [--step aoa=0.5] [--step thickness=0.02]
WORK/source is the case (made by make-naca0012-case.sh if missing; the adjoint runs in it once);
WORK/fd/<variable>_plus and _minus are the variants (linked to the source; checkMesh must pass
on each and keep the mesh 2D); WORK/validation.csv holds the table printed at the end. Two
OpenFOAM runs go at a time (the adjoint and the primal runs are serial). Run again: the runs
already done are kept.
"""
import argparse
import csv
import os
import sys
import time

from paraview.simple import LoadPlugin

parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
parser.add_argument('plugin')
parser.add_argument('work')
parser.add_argument('--primal', type=int, default=3000, help='primal iterations before the adjoint (the tutorial: 3000)')
parser.add_argument('--adjoint', type=int, default=3000, help='adjoint iterations (the tutorial: 3000)')
parser.add_argument('--fd-primal', type=int, default=5000, help='primal iterations of each finite-difference run')
parser.add_argument('--step', action='append', default=[], help='name=h: the finite-difference step of a variable')
args = parser.parse_args()
LoadPlugin(args.plugin, remote=False)
here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import mlsdeform  # noqa: E402
import naca0012  # noqa: E402

steps = {'aoa': 0.5, 'thickness': 0.02}   # degrees; thickness factor
for entry in args.step:
    name, value = entry.split('=')
    steps[name] = float(value)
work = os.path.abspath(args.work)
began = time.perf_counter()
source, deformed, dvs = naca0012.source_deformation(work, args.primal, args.adjoint)
names = dvs.getVarNames()


def objective_done(case):
    try:
        mlsdeform.readFoamObjective(case)
        return True
    except ValueError:
        return False


# the runs: the adjoint on the source, and the primal on each variant at p = +-h
jobs = []
if not any(n.startswith(naca0012.FIELD) for t in os.listdir(source) if os.path.isdir(os.path.join(source, t))
           for n in os.listdir(os.path.join(source, t))):
    jobs.append((source, lambda: naca0012.start_adjoint(source, args.primal, args.adjoint)))
variants = {}
for name in names:
    for sign, label in ((1, 'plus'), (-1, 'minus')):
        case = os.path.join(work, 'fd', '%s_%s' % (name, label))
        variants[name, sign] = case
        if objective_done(case):
            continue
        dvs.setDesignVars({n: (sign * steps[n] if n == name else 0.0) for n in names})
        dvs.update()
        quality = mlsdeform.meshQuality(dvs)
        os.makedirs(os.path.dirname(case), exist_ok=True)
        mlsdeform.foam.save_variant(deformed, os.path.join(case, 'case.foam'), overwrite=True, link=True)
        ok, log = naca0012.checkmesh(case)
        print('%s = %+g: checkMesh %s, max non-orthogonality %.2f, inverted cells %d' % (
            name, sign * steps[name], 'OK' if ok else 'FAILED', quality['MaxNonOrthogonality'], quality['InvertedCells']),
            flush=True)
        if not ok:
            sys.exit('checkMesh failed on %s:\n%s' % (case, log))
        jobs.append((case, lambda case=case: naca0012.start_adjoint(case, args.fd_primal, 0)))
dvs.setDesignVars({n: 0.0 for n in names})
running = []
while jobs or running:
    while jobs and len(running) < 2:
        case, start = jobs.pop(0)
        print('running adjointOptimisationFoam in %s' % case, flush=True)
        running.append((case, start()))
    case, process = running.pop(0)
    naca0012.finish(process, case)

# the chain and the differences
dvs.update()
J = mlsdeform.readFoamObjective(source)
adjoint = dvs.totalSensitivity(mlsdeform.readFoamSensitivity(deformed, field=naca0012.FIELD))
normal = dvs.totalSensitivity(mlsdeform.readFoamSensitivity(deformed, field=naca0012.FIELD.replace('Vec', 'Normal')))
rows = []
print('\nJ = %.10g at p = 0 (drag objective)' % J)
print('%-10s %8s %14s %14s %14s %8s' % ('variable', 'h', 'adjoint', 'adjoint normal', 'central FD', 'ratio'))
for name in names:
    plus, minus = (mlsdeform.readFoamObjective(variants[name, s]) for s in (1, -1))
    fd = (plus - minus) / (2 * steps[name])
    rows.append(dict(variable=name, h=steps[name], J=J, J_plus=plus, J_minus=minus, adjoint=adjoint[name],
                     adjoint_normal=normal[name], finite_difference=fd, ratio=adjoint[name] / fd))
    print('%-10s %8g %14.6g %14.6g %14.6g %8.4f' % (name, steps[name], adjoint[name], normal[name], fd, adjoint[name] / fd))
with open(os.path.join(work, 'validation.csv'), 'w', newline='') as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
print('%.0f s; table in %s' % (time.perf_counter() - began, os.path.join(work, 'validation.csv')))
