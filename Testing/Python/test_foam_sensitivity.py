"""Issue 30 points 1 and 7: mlsdeform.readFoamSensitivity on the NACA 0012 adjoint tutorial
(Examples/OpenFOAM/make-naca0012-case.sh) after short adjointOptimisationFoam runs (the mapping,
not the converged values, is tested here; validate_naca0012_adjoint.py compares converged ones with
finite differences): each form of the surface sensitivity gives dJ/dX at the deformation's points,
each mesh point once; the normal form's normals are the solver's; the solver's default area
division is undone; the face form's values go to their faces' points; bad fields, times and cases are clear errors that leave the case as it was.
Usage: pvpython test_foam_sensitivity.py PLUGIN EXAMPLES_OPENFOAM_DIR OPENFOAM_EXAMPLES WORK_DIR"""
import gzip
import os
import re
import shutil
import subprocess
import sys

import numpy as np
from paraview.simple import LoadPlugin

plugin, examples, tutorials, work = sys.argv[1:5]
LoadPlugin(plugin, remote=False)
sys.path.insert(0, examples)
import mlsdeform  # noqa: E402
import naca0012  # noqa: E402

from checks import check, finish, raises  # noqa: E402

ITERATIONS = 50    # primal and adjoint: enough for non-trivial fields, far from converged


def field_file(case, name):
    time = max((d for d in os.listdir(case) if re.fullmatch(r'[0-9.e+-]+', d) and float(d) > 0), key=float)
    return os.path.join(case, time, name + '.gz')


def parse_field(path):
    """The internal field of an ascii point field file (gzipped): an (N,) or (N, 3) array."""
    with gzip.open(path, 'rt') as f:
        text = f.read()
    body = text[text.index('internalField'):]
    count = int(re.search(r'List<\w+>\s+(\d+)', body).group(1))
    start = body.index('(', body.index(str(count)))
    numbers = np.array(re.findall(r'[-+0-9.eE]+', body[start:body.index('boundaryField')]), dtype=float)
    return numbers[:count] if 'List<scalar>' in body else numbers[:3 * count].reshape(count, 3)


def write_field(path, template, values):
    """A copy of the field file template with another internal field (ascii, gzipped)."""
    with gzip.open(template, 'rt') as f:
        text = f.read()
    head, tail = text[:text.index('internalField')], text[text.index('boundaryField'):]
    rows = '\n'.join('(%r %r %r)' % tuple(v) for v in values)
    with gzip.open(path, 'wt') as f:
        f.write(head + 'internalField   nonuniform List<vector>\n%d\n(\n%s\n)\n;\n\n' % (len(values), rows) + tail)


# Two runs of the same case: the sensitivity as dJ/dx (make-naca0012-case.sh sets
# includeSurfaceArea true) and as the solver's default, divided by each point's face area.
source, divided, faces = os.path.join(work, 'source'), os.path.join(work, 'divided'), os.path.join(work, 'faces')
subprocess.run(['bash', os.path.join(examples, 'make-naca0012-case.sh'), source, str(ITERATIONS), str(ITERATIONS), tutorials],
               check=True)
shutil.copytree(source, divided)
shutil.copytree(source, faces)
for case, entry in ((divided, 'includeSurfaceArea -set false'), (faces, 'type -set surface')):
    subprocess.run(['bash', '-c', 'source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1; foamDictionary -entry '
                    'optimisation.sensitivities.%s %s/system/optimisationDict > /dev/null' % (entry, case)], check=True)
runs = [(case, naca0012.start_adjoint(case, ITERATIONS, ITERATIONS)) for case in (source, divided, faces)]
for case, process in runs:
    naca0012.finish(process, case)
before = sorted(os.listdir(source))

deformed, dvs = naca0012.deformation(os.path.join(source, 'case.foam'))
output = dvs._algorithm.GetOutputDataObject(0)
n = output.GetNumberOfPoints()
mesh_points = 76806

vec = mlsdeform.readFoamSensitivity(deformed, field='pointSensVecadjS1ESI', time='latest')
check(vec.shape == (n, 3), 'dJ/dX has a row per output point (%s)' % (vec.shape,))
rows = np.flatnonzero(np.abs(vec).sum(axis=1) > 0)
check(len(rows) == 796 and rows.max() < mesh_points,
      'dJ/dX is non-zero at the airfoil points only (398 points on each of 2 planes), each once at the internal mesh: %d rows, last %d'
      % (len(rows), rows.max()))
raw = parse_field(field_file(source, 'pointSensVecadjS1ESI'))
scale = np.abs(raw).sum()
check(np.abs(vec.sum(axis=0) - raw.sum(axis=0)).max() <= 1e-6 * scale,
      "dJ/dX sums to the field's sum (float32 reading: 1e-6 of sum |v|): %s vs %s" % (vec.sum(axis=0), raw.sum(axis=0)))
check(np.abs(vec[:mesh_points] - raw).max() <= 1e-6 * np.abs(raw).max(),
      'dJ/dX at the internal mesh is the field, point by point (max difference %.3g)' % np.abs(vec[:mesh_points] - raw).max())

# the normal form times the normals computed here equals the solver's own normal vectors
normal = mlsdeform.readFoamSensitivity(deformed, field='pointSensNormaladjS1ESI')
normal_vec = mlsdeform.readFoamSensitivity(deformed, field='pointSensNormalVecadjS1ESI')
check(np.abs(normal - normal_vec).max() <= 1e-5 * np.abs(normal_vec).max(),
      "the normal form with this module's point normals is the solver's pointSensNormalVec (max difference %.3g of %.3g)"
      % (np.abs(normal - normal_vec).max(), np.abs(normal_vec).max()))
# the solver's default divides by each point's face area: undone, the two runs agree to the
# areas' precision from the reader's float32 points: the shortest wall edge (5e-3 long, at |x| ~ 0.5)
# is known to 6e-8 * 0.5 / 5e-3 = 6e-6 of its length, so 1e-5 of the largest value
for field, full in (('pointSensVecadjS1ESI', vec), ('pointSensNormaladjS1ESI', normal)):
    undivided = mlsdeform.readFoamSensitivity(deformed, field=field, case=divided)
    gap = np.abs(undivided - full).max()
    check(gap <= 1e-5 * np.abs(full).max(), '%s of the area-divided run times A_p is the dJ/dx run (max difference %.3g of %.3g)'
          % (field, gap, np.abs(full).max()))

# the face form (type surface): each face's value shared by its points; a rigid translation moves
# every face alike, so the total is the point form's (to the float32 values' precision), and
# reading it warns that the form misses the faces' area and normal changes
import warnings  # noqa: E402
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter('always')
    face = mlsdeform.readFoamSensitivity(deformed, field='faceSensVecadjS1ESI', case=faces)
check(any('prefer `type surfacePoints`' in str(w.message) for w in caught), 'reading a face field warns')
check(np.abs(face.sum(axis=0) - vec.sum(axis=0)).max() <= 1e-5 * np.abs(vec).sum(),
      "the face form's total is the point form's: %s vs %s" % (face.sum(axis=0), vec.sum(axis=0)))
check(np.count_nonzero(np.abs(face).sum(axis=1) > 0) == 796, 'the face form reaches the same 796 points')

g = dvs.totalSensitivity(vec)
check(all(np.isfinite(v) and v != 0 for v in g.values()), 'dJ/dp of both variables: %s' % g)
# the serial answer for Python.FoamSensitivity.Ranks2 (test_foam_sensitivity_ranks.py)
rest = np.concatenate([np.array(mlsdeform.adjoint._points(d)) for _, d in
                       mlsdeform.adjoint._leaves(dvs._algorithm.GetInputDataObject(0, 0))])
np.savez(os.path.join(work, 'reference.npz'), rest=rest, dJdX=vec, dJdp=np.array([g[n] for n in dvs.getVarNames()]))
J = mlsdeform.readFoamObjective(source)
check(np.isfinite(J) and J > 0, 'J from the objective history: %r' % J)

# bad input: each a ValueError naming what is wrong; the case stays as it was
raises(lambda: mlsdeform.readFoamSensitivity(deformed, field='pointSensVecadjS9ESI'), "no time of", 'a missing field')
raises(lambda: mlsdeform.readFoamSensitivity(deformed, field='U'), 'is not a sensitivity field', 'a field that is no sensitivity')
raises(lambda: mlsdeform.readFoamSensitivity(deformed, field='pointSensVecadjS1ESI', time=12345), 'has no time 12345',
       'a time the case does not have')
dvs.setDesignVars({'aoa': 1.0})
raises(lambda: mlsdeform.readFoamSensitivity(deformed, field='pointSensVecadjS1ESI'), "not the deformation's current shape",
       'a case of another shape than the deformation now has')
dvs.setDesignVars({'aoa': 0.0})
far = os.path.join(work, 'farfield')
shutil.copytree(source, far)
points_far = np.abs(raw).sum(axis=1) == 0
template = field_file(source, 'pointSensVecadjS1ESI')
elsewhere = np.zeros_like(raw)
elsewhere[points_far] = [1.0, 0.0, 0.0]
write_field(field_file(far, 'pointSensVecadjS1ESI'), template, elsewhere)
raises(lambda: mlsdeform.readFoamSensitivity(deformed, field='pointSensVecadjS1ESI', case=far),
       'zero at every point of the Handle regions', 'a field on other points than the handles')
write_field(field_file(far, 'pointSensVecadjS1ESI'), template, raw[:-10])
raises(lambda: mlsdeform.readFoamSensitivity(deformed, field='pointSensVecadjS1ESI', case=far), 'pointSensVecadjS1ESI',
       'a field of the wrong size')
os.makedirs(os.path.join(far, 'processor0', '400'))
shutil.copyfile(template, os.path.join(far, 'processor0', '400', 'pointSensVecadjS2ESI.gz'))
raises(lambda: mlsdeform.readFoamSensitivity(deformed, field='pointSensVecadjS2ESI', case=far), 'run reconstructPar',
       'a field of a decomposed run, in the processor folders only')
os.remove(os.path.join(far, 'system', 'optimisationDict'))
raises(lambda: mlsdeform.readFoamSensitivity(deformed, field='pointSensVecadjS1ESI', case=far), 'has no system/optimisationDict',
       'a case without optimisationDict')
raises(lambda: mlsdeform.readFoamObjective(far + '-missing'), 'has no optimisation/objective', 'an objective of a case that did not run')
check(sorted(os.listdir(source)) == before, 'the source case holds the same files as before')

finish()
