"""MLS Deform measures an OpenFOAM case's mesh quality on the case's own faces (constant/polyMesh:
faces, owner, neighbour, read ahead while VTK's reader reads the case: mlsdeform.vtkfoam.open_case)
when the grid is that case's mesh as OpenFOAM numbers it, and otherwise matches the grid's cell
faces by their points. Both give the same figures; VTK's trace log tells which ran. On the
sphereChannel case (built here), in python3 on a plain VTK pipeline.
Usage: python3 test_case_faces.py PLUGIN_FILE EXAMPLES_OPENFOAM_DIR WORK_DIR"""
import os
import shutil
import subprocess
import sys

plugin, examples, work = sys.argv[1:4]
sys.path.insert(0, os.path.dirname(os.path.abspath(plugin)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mlsdeform  # noqa: E402
from mlsdeform import vtkfoam  # noqa: E402
from vtkmodules.vtkCommonCore import vtkLogger  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet  # noqa: E402

from checks import check, finish  # noqa: E402

FIGURES = ('InvertedCells', 'MaxNonOrthogonality', 'MaxSkewness', 'OriginalInvertedCells', 'OriginalMaxNonOrthogonality',
           'OriginalMaxSkewness')
READ = "mesh quality: the case's faces, owner and neighbour"   # the case's faces read
TAKEN = "mesh quality: the case's cells against the grid's"    # ... and found to be the grid's cells
MATCHED = 'mesh quality: interior and boundary faces'                       # the grid's faces matched by their points
FIGURES_AHEAD = "the case's points are the grid's"             # the undeformed figures read with the faces
AHEAD = "{ mesh quality: the case's faces read ahead"           # a read ahead started
handle, fixed, slip = ['body'], ['inlet', 'outlet'], ['ground', 'top', 'front', 'back']
motion = (0.05, 0, 0.02)


def deformed_figures(name, case, decompose_polyhedra=False, strip_case_path=False, ahead=None):
    """The quality figures MLS Deform reports for the sphere moved by motion, and VTK's trace log
    of the run. ahead: the case whose faces are read ahead before the reader's update (default: this
    one, as open_case does; '': none, MLS Deform then reads them while it sets up)."""
    log = os.path.join(work, name + '.log')
    vtkLogger.LogToFile(log, vtkLogger.TRUNCATE, vtkLogger.VERBOSITY_TRACE)
    if ahead is None:
        reader = vtkfoam.open_case(os.path.join(case, 'case.foam'), handle + fixed + slip, decompose_polyhedra)
    else:
        if ahead:
            mlsdeform._load_wrapping().vtkSubspaceDeformFilter.PrefetchCaseFaces(ahead)
        reader = vtkfoam.configured_reader(os.path.join(case, 'case.foam'), handle + fixed + slip, decompose_polyhedra)
        reader.Update()
    if strip_case_path:
        # the same mesh without the reader's CasePath: MLS Deform cannot know its case
        copy = vtkMultiBlockDataSet()
        copy.ShallowCopy(reader.GetOutput())
        copy.GetFieldData().RemoveArray('CasePath')
        reader.GetOutput().ShallowCopy(copy)
    deform = vtkfoam.morph(reader, handle, motion, fixed, slip)
    vtkLogger.EndLogToFile(log)
    field = deform.GetOutputDataObject(0).GetFieldData()
    figures = {n: field.GetArray(n).GetTuple1(0) for n in FIGURES}
    with open(log) as f:
        text = f.read()
    return figures, text


def same(a, b):
    """The figures agree to round-off: the two sum each cell's face terms in another order, a few
    dozen operations on float32 coordinates per measure (1e-12 relative)."""
    return all(abs(a[n] - b[n]) <= 1e-12 * max(1.0, abs(a[n])) for n in FIGURES)


case = os.path.join(work, 'case')
subprocess.run(['bash', os.path.join(examples, 'make-case.sh'), case], check=True)

own, log = deformed_figures('own', case)
check(READ in log and TAKEN in log and MATCHED not in log and FIGURES_AHEAD in log,
      "the case's own faces measured its mesh (read ahead with the undeformed figures, then checked)")
matched, log = deformed_figures('matched', case, strip_case_path=True)
check(TAKEN not in log and MATCHED in log, 'a mesh without CasePath has its faces matched by their points')
check(same(own, matched), 'both give the same figures: %s' % own)
check(own['OriginalMaxNonOrthogonality'] > 10 and own['InvertedCells'] == 0, 'the figures are a real mesh\'s')

# Decompose polyhedra on: VTK's cells are not OpenFOAM's (more points), so the faces read ahead (the
# run before left its read, which had no CasePath to take it) are left and the grid's matched
_, log = deformed_figures('decomposed', case, decompose_polyhedra=True)
check(TAKEN not in log and MATCHED in log, "VTK's decomposed cells: the case's faces are not the grid's, matched instead")

# A mesh whose cells change in time (a time folder with faces of its own): matched
changing = os.path.join(work, 'changing')
shutil.copytree(case, changing, symlinks=True)
shutil.copytree(os.path.join(changing, 'constant', 'polyMesh'), os.path.join(changing, '1', 'polyMesh'))
moving, log = deformed_figures('changing', changing)
check(MATCHED in log and TAKEN not in log, 'a case whose time folders hold faces: matched')
check(same(moving, own), 'with the same figures')

# A mesh moved in time (a time folder with points of its own, here a variant's): the case's faces,
# but the undeformed figures of the grid's points, not of constant/polyMesh/points
moved = os.path.join(work, 'moved')
shutil.copytree(case, moved, symlinks=True)
reader = vtkfoam.open_case(os.path.join(case, 'case.foam'), handle + fixed + slip, False)
vtkfoam.save_variant(vtkfoam.morph(reader, handle, motion, fixed, slip), os.path.join(work, 'variant', 'case.foam'))
os.makedirs(os.path.join(moved, '1', 'polyMesh'))
shutil.copy(os.path.join(work, 'variant', 'constant', 'polyMesh', 'points'), os.path.join(moved, '1', 'polyMesh', 'points'))
from_moved, log = deformed_figures('moved', moved)
check(TAKEN in log and FIGURES_AHEAD not in log, "a mesh moved in time: the case's faces, the grid's own undeformed figures")
check(same(from_moved, deformed_figures('moved-matched', moved, strip_case_path=True)[0]) and
      from_moved['OriginalMaxNonOrthogonality'] != own['OriginalMaxNonOrthogonality'],
      'the same figures as matched faces give, those of the moved mesh: %s' % from_moved)

# Faces read ahead for another case are not taken (but dropped); with those, or with nothing read
# ahead by the script (a pipeline without open_case, as the GUI's), MLS Deform reads this case's
# faces ahead as its set-up starts and takes them: they are read once, and that read is ahead
for name, ahead in (('other', changing), ('none', '')):
    figures, log = deformed_figures(name, case, ahead=ahead)
    reads = 2 if ahead else 1
    check(log.count(AHEAD) == reads and log.count('{ ' + READ) == reads and TAKEN in log and same(figures, own),
          "with %s read ahead by the script, MLS Deform reads this case's faces ahead and takes them, the same figures" %
          ('another case' if ahead else 'nothing'))
finish()
