"""Issue 14: a decomposed OpenFOAM case (processor0..3 of the sphereChannel case, made by
Examples/OpenFOAM/make-case.sh CASE decompose) read in parallel, deformed and saved.

  pvbatch test_openfoam_decomposed.py PLUGIN CASE WORK reference
      on one process: the deformation of the case read decomposed (all four folders), kept in
      WORK/reference.npz; and the same case read reconstructed gives the same deformation when
      the reader keeps polyhedra (with Decompose polyhedra the reader splits a polyhedron's faces
      by their orientation in each processor's mesh, so the two readings are different
      tetrahedralizations: a different sample draw);
  mpiexec -n N pvbatch test_openfoam_decomposed.py PLUGIN CASE WORK compare
      reads the processor folders in parallel (process r: folders r, r + N, ...), deforms them,
      checks every point against the reference, saves the variant WORK/variantN with SaveData
      (every process writes its folders) and checks the written points;
  pvpython test_openfoam_decomposed.py PLUGIN CASE WORK checkmesh N
      runs OpenFOAM's checkMesh -parallel on 4 processes and checkMesh on the reconstructed mesh
      of WORK/variantN: no check fails that passed on the source.
"""
import os
import subprocess
import sys

import numpy as np

plugin, case, work, mode = sys.argv[1:5]
failures = []


def check(condition, what):
    print(('ok   ' if condition else 'FAIL ') + what, flush=True)
    if not condition:
        failures.append(what)


def finish():
    """Exits non-zero after a failed check. (pvbatch must reach the script's end after success:
    its other processes wait for the first one there.)"""
    if failures:
        print('%d check(s) failed' % len(failures))
        sys.exit(1)


def openfoam(command, folder):
    # without the MPI environment of this process (pvpython starts MPI as a singleton), in which
    # mpirun would take itself for a child of this job and start nothing
    environment = {k: v for k, v in os.environ.items() if not k.startswith(('OMPI_', 'PMIX_', 'OPAL_'))}
    run = subprocess.run(['bash', '-c', 'source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1; %s -case "%s"' % (command, folder)],
                         capture_output=True, text=True, env=environment)
    return run.stdout + run.stderr


def failed_checks(log):
    """checkMesh's count of failed checks (0 when the mesh is OK, None when it did not run)."""
    if 'Mesh OK.' in log:
        return 0
    for line in log.splitlines():
        if 'Failed' in line and 'mesh checks' in line:
            return int(line.split('Failed')[1].split()[0])
    return None


if mode == 'checkmesh':
    variant = os.path.join(work, 'variant%s' % sys.argv[5])
    mpirun = 'mpirun --allow-run-as-root --oversubscribe -np 4'
    for name, command in (('checkMesh -parallel', mpirun + ' checkMesh -parallel'), ('checkMesh', 'checkMesh')):
        source, log = failed_checks(openfoam(command, case)), failed_checks(openfoam(command, variant))
        check(source == 0 and log == 0, '%s passes on the source (%s failed) and on the variant (%s failed)' % (name, source, log))
    finish()
    sys.exit(0)  # pvpython, one process

import paraview.simple as pvs
from paraview import servermanager
from vtk.numpy_interface import dataset_adapter as dsa

pvs.LoadPlugin(plugin, remote=False)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'Examples', 'OpenFOAM'))
import openfoam_variant  # noqa: E402

PATCHES = ['body', 'inlet', 'outlet', 'top', 'front', 'back', 'ground']


def deformed(case_type, polyhedra):
    """The case read as case_type, its rest positions in a point array, deformed: the body moved,
    the far field fixed, the ground slipping."""
    reader = pvs.OpenFOAMReader(FileName=os.path.join(case, 'case.foam'))
    reader.CaseType = case_type
    reader.MeshRegions = ['internalMesh'] + ['patch/' + p for p in PATCHES]
    reader.Decomposepolyhedra = polyhedra
    rest = pvs.Calculator(Input=reader, AttributeType='Point Data', ResultArrayName='Rest', Function='coords',
                          ResultArrayType='Double')
    return openfoam_variant.morph(rest, ['body'], [0.1, 0.05, 0.0], fixed=['inlet', 'outlet', 'top', 'front', 'back'],
                                  slip=['ground'])


def gathered(proxy):
    """Rest positions and Displacement of every point of every block, gathered on the client, and
    the numeric field data."""
    data = servermanager.Fetch(proxy)
    rest, displacement = [], []
    for block in dsa.WrapDataObject(data):
        if block.GetNumberOfPoints() == 0:
            continue
        rest.append(np.asarray(block.PointData['Rest']))
        displacement.append(np.asarray(block.VTKObject.GetPointData().GetArray('Displacement')))
    fields = data.GetFieldData()
    field = {fields.GetArrayName(a): fields.GetArray(a).GetTuple1(0) for a in range(fields.GetNumberOfArrays())
             if fields.GetArray(a) is not None and fields.GetArrayName(a) != 'CasePath'}
    return np.concatenate(rest), np.concatenate(displacement), field


def deviation(rest, displacement, reference_rest, reference_displacement):
    """The largest distance of a point's displacement from the reference's at the same rest
    position, over the diagonal; None when a point is not in the reference."""
    index = {tuple(x): i for i, x in enumerate(reference_rest)}
    which = np.array([index.get(tuple(x), -1) for x in rest])
    if (which < 0).any():
        return None
    diagonal = np.linalg.norm(reference_rest.max(axis=0) - reference_rest.min(axis=0))
    return np.linalg.norm(displacement - reference_displacement[which], axis=1).max() / diagonal


def foam_points(path):
    """The double coordinates of an ascii OpenFOAM points file."""
    with open(path) as f:
        text = f.read()
    body = text[text.index('(', text.index('}')) + 1:]
    rows = [line.strip()[1:-1].split() for line in body.splitlines() if line.strip().startswith('(')]
    return np.array(rows, dtype=float)


def reference():
    """The serial deformation of the case read decomposed, and the reconstructed reading."""
    os.makedirs(work, exist_ok=True)
    rest, displacement, field = gathered(deformed('Decomposed Case', 1))
    check(np.linalg.norm(displacement, axis=1).max() > 0.05, 'the body moves the mesh')
    np.savez(os.path.join(work, 'reference.npz'), rest=rest, displacement=displacement, **field)
    # a processor's cells split into simplices as the whole mesh's are: the same samples
    whole = gathered(deformed('Reconstructed Case', 0))
    parts = gathered(deformed('Decomposed Case', 0))
    d = deviation(parts[0], parts[1], whole[0], whole[1])
    check(d is not None and d <= 1e-10, 'read decomposed or reconstructed (polyhedra kept): the same deformation (%s)' % d)
    # and the same mesh quality: the faces between the processor folders' pieces are measured
    # across them, as checkMesh measures a processor patch (the deformations agree to 1e-10 of
    # the diagonal, the cells are 1e-3 of it: 1e-7 relative; 1e-6 allowed)
    for name in ('MaxNonOrthogonality', 'MaxSkewness', 'OriginalMaxNonOrthogonality', 'OriginalMaxSkewness'):
        check(name in whole[2] and name in parts[2] and np.isclose(parts[2][name], whole[2][name], rtol=1e-6, atol=0),
              '%s read decomposed %s, reconstructed %s' % (name, parts[2].get(name), whole[2].get(name)))


def compare():
    """The processor folders read in parallel, deformed and saved."""
    ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
    serial = np.load(os.path.join(work, 'reference.npz'))
    deform = deformed('Decomposed Case', 1)
    rest, displacement, field = gathered(deform)
    d = deviation(rest, displacement, serial['rest'], serial['displacement'])
    # issue 14's bound: the serial position within 1e-10 of the diagonal
    check(d is not None and d <= 1e-10, '%d ranks: every point within 1e-10 of the diagonal of its serial position (%s)' % (ranks, d))
    order = np.lexsort(rest.T)
    same = (np.diff(rest[order], axis=0) == 0).all(axis=1)
    check(same.any() and np.abs(np.diff(displacement[order], axis=0)[same]).max() == 0,
          'points that two processor folders (or a patch and the internal mesh) share are identical (%d)' % same.sum())
    for name in ('HandleResidual', 'FixedResidual', 'ConstraintPoints', 'InvertedCells', 'MaxNonOrthogonality', 'MaxSkewness',
                 'OriginalMaxSkewness'):
        check(name in field and np.isclose(field[name], serial[name], rtol=1e-9, atol=1e-14),
              '%s is the serial one (%s, serial %s)' % (name, field.get(name), serial[name] if name in serial else None))

    # the variant, written by every process: each processor folder's points and the reconstructed
    # mesh are the source's double points plus the displacement at their position (float32 as read)
    variant = os.path.join(work, 'variant%d' % ranks)
    pvs.SaveData(os.path.join(variant, 'case.foam'), proxy=deform, Overwrite=1)
    by_position = {tuple(x): u for x, u in zip(rest, displacement)}
    folders = ['constant'] + ['processor%d/constant' % p for p in range(4)]
    for folder in folders:
        source = foam_points(os.path.join(case, folder, 'polyMesh', 'points'))
        written = foam_points(os.path.join(variant, folder, 'polyMesh', 'points')) if os.path.exists(
            os.path.join(variant, folder, 'polyMesh', 'points')) else np.zeros((0, 3))
        keys = source.astype(np.float32).astype(float)
        expected = source + np.array([by_position.get(tuple(k), np.full(3, np.nan)) for k in keys])
        check(written.shape == source.shape and np.array_equal(written, expected),
              '%s/polyMesh/points: the source\'s points plus the displacement (%d points)' % (folder, len(written)))
    # saved again without Overwrite: rank 0 finds the target, every rank stops (none waits for
    # the others), and the variant is as it was
    stamps = [os.stat(os.path.join(variant, folder, 'polyMesh', 'points')).st_mtime_ns for folder in folders]
    pvs.SaveData(os.path.join(variant, 'case.foam'), proxy=deform, Overwrite=0)
    check(stamps == [os.stat(os.path.join(variant, folder, 'polyMesh', 'points')).st_mtime_ns for folder in folders] and
          not [f for f in os.listdir(work) if '.writing-' in f], 'an existing target stops every rank and writes nothing')


if mode == 'reference':
    reference()
else:
    compare()
finish()
