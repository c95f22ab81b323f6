"""Issue 12: an OpenFOAM snappyHexMesh case (Examples/OpenFOAM/sphereChannel, built here with
blockMesh and snappyHexMesh) read, deformed and written back, with Decompose polyhedra on and
off. Usage: pvpython test_openfoam_roundtrip.py PLUGIN EXAMPLES_OPENFOAM_DIR WORK_DIR"""
import os
import shutil
import subprocess
import sys

import numpy as np
from paraview import servermanager
import paraview.simple as pvs
from paraview.simple import LoadPlugin
from vtk.util.numpy_support import vtk_to_numpy

plugin, examples, work = sys.argv[1:4]
LoadPlugin(plugin, remote=False)
sys.path.insert(0, examples)
import openfoam_variant  # noqa: E402
import foam_box  # noqa: E402  (beside this script)

failures = []


def check(condition, what):
    print(('ok   ' if condition else 'FAIL ') + what)
    if not condition:
        failures.append(what)


def openfoam(command, case):
    """Runs an OpenFOAM command in case; returns its output."""
    return subprocess.run(['bash', '-c', 'source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1; cd "%s" && %s' % (case, command)],
                          capture_output=True, text=True).stdout


def points_file(case):
    """The double coordinates of an ascii constant/polyMesh/points (n x 3)."""
    text = open(os.path.join(case, 'constant', 'polyMesh', 'points')).read()
    body = text[text.index('\n(', text.index('FoamFile')) + 2:]
    rows = [line.strip()[1:-1].split() for line in body.splitlines() if line.startswith('(')]
    return np.array([[float(v) for v in row] for row in rows])


def blocks(data):
    """name -> leaf of a multiblock."""
    out = {}
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        out[it.GetCurrentMetaData().Get(data.NAME())] = it.GetCurrentDataObject()
        it.GoToNextItem()
    return out


def failed_checks(log):
    for line in log.splitlines():
        if 'Failed' in line and 'mesh checks' in line:
            return int(line.split()[1])
    return 0 if 'Mesh OK.' in log else -1


case = os.path.join(work, 'case')
subprocess.run(['bash', os.path.join(examples, 'make-case.sh'), case], check=True)
source = points_file(case)
source_log = openfoam('checkMesh', case)
motion = np.array([0.05, 0.0, 0.02])
diagonal = np.linalg.norm(source.max(axis=0) - source.min(axis=0))
handle, fixed, slip = ['body'], ['inlet', 'outlet'], ['ground', 'top', 'front', 'back']
for decompose in (True, False):
    print('Decompose polyhedra %s' % decompose)
    reader = openfoam_variant.open_case(os.path.join(case, 'case.foam'), handle + fixed + slip, decompose)
    deformed = openfoam_variant.morph(reader, handle, motion, fixed, slip)
    variant = os.path.join(work, 'variant-%d' % decompose)
    openfoam_variant.save_variant(deformed, os.path.join(variant, 'case.foam'), overwrite=True)
    before, after = blocks(servermanager.Fetch(reader)), blocks(servermanager.Fetch(deformed))
    mesh = after['internalMesh']
    d = vtk_to_numpy(mesh.GetPointData().GetArray('Displacement'))
    n = len(source)
    check(mesh.GetNumberOfPoints() >= n and (decompose or mesh.GetNumberOfPoints() == n),
          'the internal mesh holds the case\'s %d points first (%d with decomposition points)' % (n, mesh.GetNumberOfPoints()))
    written = points_file(variant)
    check(written.shape == source.shape, 'point count kept: %d' % len(written))
    check(np.array_equal(written, source + d[:n]), 'written points = the source\'s double points + Displacement, exactly')
    # points a patch shares with the internal mesh move alike (same rest position, same d(x))
    rest = {tuple(p): i for i, p in enumerate(vtk_to_numpy(before['internalMesh'].GetPoints().GetData()))}
    moved = vtk_to_numpy(mesh.GetPoints().GetData())
    for name in handle + fixed + slip:
        patch_rest = vtk_to_numpy(before[name].GetPoints().GetData())
        patch_moved = vtk_to_numpy(after[name].GetPoints().GetData())
        ids = [rest.get(tuple(p), -1) for p in patch_rest]
        check(min(ids) >= 0 and np.array_equal(patch_moved, moved[ids]), 'patch %s: its points equal the internal mesh\'s' % name)
        u = vtk_to_numpy(after[name].GetPointData().GetArray('Displacement'))
        target = motion if name in handle else np.zeros(3)
        if name not in slip:
            # exact targets (the default): round-off of the double displacement, the 1e-9
            # of the diagonal (the penalty solution of eq. 14 alone missed by 0.1% of the motion)
            error = np.linalg.norm(u - target, axis=1).max() / diagonal
            check(error <= 1e-9, 'patch %s meets its target exactly (%.2g of the diagonal)' % (name, error))
    # slip planes: x, y or z of their points unchanged, exactly (OpenFOAM's slip keeps them on it)
    for axis, value, name in ((2, -1.25, 'ground'), (2, 4.25, 'top'), (1, -4.25, 'front'), (1, 4.25, 'back')):
        on = source[:, axis] == value
        slide = np.abs(written[on] - source[on]).max()
        check(on.sum() > 0 and np.array_equal(written[on, axis], source[on, axis]),
              'slip %s: %d points stay on their plane (largest slide %.3g)' % (name, on.sum(), slide))
    log = openfoam('checkMesh', variant)
    check(failed_checks(log) == 0 and failed_checks(source_log) == 0, 'checkMesh passes on the variant')
    # the quality MLS Deform reports is checkMesh's (on OpenFOAM's own cells: polyhedra kept)
    # (with Decompose polyhedra on, VTK's decomposed cells may share a face three ways: not reported)
    if not decompose:
        field = deformed.GetDataInformation().GetFieldDataInformation()
        reported = {n: field.GetArrayInformation(n).GetComponentRange(0)[0]
                    for n in ('InvertedCells', 'OriginalInvertedCells', 'MaxNonOrthogonality', 'MaxSkewness', 'OriginalMaxNonOrthogonality')}
        # checkMesh's face-pyramid test: the source passes it, and so must the variant
        check(reported['InvertedCells'] == 0 and reported['OriginalInvertedCells'] == 0,
              'no inverted cell (%d with a face pyramid of negative volume, %d in the source)'
              % (reported['InvertedCells'], reported['OriginalInvertedCells']))
        for name, source_name, key in (('MaxNonOrthogonality', 'variant', 'non-orthogonality Max:'),
                                       ('MaxSkewness', 'variant', 'Max skewness ='),
                                       ('OriginalMaxNonOrthogonality', 'source', 'non-orthogonality Max:')):
            line = [x for x in (log if source_name == 'variant' else source_log).splitlines() if key in x][0]
            expected = float(line.split(key)[1].split()[0])
            # checkMesh prints 12 significant digits (writePrecision); the reader's float32 points
            # perturb the geometry by eps_f |x|: allow 1e-5 relative
            check(abs(reported[name] - expected) <= 1e-5 * expected,
                  '%s %.9g matches checkMesh\'s %.9g' % (name, reported[name], expected))

# A parallelepiped (a box sheared by 0.6 along x per unit of z): its cells are equal, so its
# interior faces have no skewness (0 to round-off) and its largest is a boundary face's, which
# checkMesh measures with the owner mirrored across the face. The reported skewness before and
# after a morph must be checkMesh's (interior faces alone would report 0 for the source).
sheared = os.path.join(work, 'sheared')
foam_box.box_case(sheared, [(x + 0.6 * z, y, z) for x, y, z in foam_box.BOX])
reader = openfoam_variant.open_case(os.path.join(sheared, 'case.foam'), ['lid', 'base', 'sides'], False)
deformed = openfoam_variant.morph(reader, ['lid'], [0.15, 0.05, 0.1], fixed=['base'])
openfoam_variant.save_variant(deformed, os.path.join(work, 'sheared-variant', 'case.foam'), overwrite=True)
field = deformed.GetDataInformation().GetFieldDataInformation()
for name, folder in (('OriginalMaxSkewness', sheared), ('MaxSkewness', os.path.join(work, 'sheared-variant'))):
    line = [x for x in openfoam('checkMesh', folder).splitlines() if 'Max skewness =' in x][0]
    expected = float(line.split('Max skewness =')[1].split()[0])
    reported = field.GetArrayInformation(name).GetComponentRange(0)[0]
    # the 1e-5 of the case above (float32 points)
    check(expected > 0.1 and abs(reported - expected) <= 1e-5 * expected,
          'sheared box: %s %.9g matches checkMesh\'s %.9g (a boundary face\'s)' % (name, reported, expected))

# Samples follow the mesh's grading (the default): the sphere is 3% of the domain's length, but
# the refined cells around it hold about a third of the mesh, and so should the MLS samples. A
# uniform sampling puts about the volume share there (0.3%): require half the mesh's share.
reader = openfoam_variant.open_case(os.path.join(case, 'case.foam'), handle + fixed + slip, False)
mesh_points = vtk_to_numpy(blocks(servermanager.Fetch(reader))['internalMesh'].GetPoints().GetData())
near = lambda x: np.linalg.norm(x, axis=1) < 0.6  # within 2.4 sphere radii of its centre
sampler = pvs.MLSSampler(Input=reader, NumberOfSurfaceSamples=750, NumberOfVolumeSamples=250)
samples = vtk_to_numpy(servermanager.Fetch(sampler).GetPoints().GetData())
check(near(samples).mean() >= 0.5 * near(mesh_points).mean(),
      'MLS samples near the body: %.1f%% (the mesh\'s points: %.1f%%)' % (100 * near(samples).mean(), 100 * near(mesh_points).mean()))

# The example end to end (point 7): morph with the boundary-layer cells of the sphere kept rigid,
# checkMesh and 2 iterations of simpleFoam on the variant (morph_case.py exits non-zero otherwise)
example = subprocess.run([shutil.which('pvpython') or sys.executable, os.path.join(examples, 'morph_case.py'), plugin, os.path.join(case, 'case.foam'),
                          os.path.join(work, 'variant-example'), '--rigid-layers', '3', '--check', '2'],
                         capture_output=True, text=True)
print(example.stdout.strip())
check(example.returncode == 0 and 'Mesh OK' in example.stdout and 'simpleFoam: ' in example.stdout,
      'morph_case.py with rigid boundary-layer cells: checkMesh and simpleFoam run on the variant')

# A newcomer's mistakes say what to change: a variant written over its source raises the writer's
# reason (not silence), a folder named instead of a .foam file is refused before anything is
# written; and the plugin loaded with ns=globals(), as paraview.simple's documentation says, still
# gives mlsdeform.foam its filters
reader = openfoam_variant.open_case(os.path.join(case, 'case.foam'), handle + fixed + slip)
deformed = openfoam_variant.morph(reader, handle, motion, fixed, slip)
for target, expected in ((os.path.join(case, 'case.foam'), 'is the source case itself'), (os.path.join(work, 'a-folder'), 'is not a .foam file')):
    try:
        openfoam_variant.save_variant(deformed, target, overwrite=True)
        raised = ''
    except (RuntimeError, ValueError) as error:
        raised = str(error)
    check(expected in raised and not os.path.exists(os.path.join(work, 'a-folder')), 'save_variant to %s raises: %s' % (target, raised))
script = ("from paraview.simple import *\nLoadPlugin(%r, remote=False, ns=globals())\nfrom mlsdeform import foam\n"
          "reader = foam.open_case(%r, ['body', 'inlet', 'outlet'])\nfoam.morph(reader, ['body'], (0.01, 0, 0), ['inlet', 'outlet'])\n"
          "print('morphed')\n" % (plugin, os.path.join(case, 'case.foam')))
loaded = subprocess.run([shutil.which('pvpython') or sys.executable, '-c', script], capture_output=True, text=True)
check(loaded.returncode == 0 and 'morphed' in loaded.stdout, 'LoadPlugin(ns=globals()) then mlsdeform.foam.morph works (%s)' %
      loaded.stderr.strip()[-300:])

if failures:
    print('%d check(s) failed' % len(failures))
    sys.exit(1)
print('all checks passed')
