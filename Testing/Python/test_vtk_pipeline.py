"""A plain VTK pipeline in python3, without ParaView's server manager: ParaView's VTK modules, the
plugin's wrapped filters and case writer and the mlsdeform package beside the plugin
(mlsdeform.vtkfoam) read the sphereChannel case (built here), deform it (the sphere moved by
(0.05, 0, 0.02), inlet and outlet Fixed, the other planes Slip) and write a linked variant case.
The variant's points file must be, byte for byte, the one pvpython writes through mlsdeform.foam
(Examples/OpenFOAM/morph_case.py with its defaults); a bad target is refused with nothing written.
mlsdeform.DesignVariables drives the VTK filter as it drives a proxy: variables written to the
vtkConstraintRegion are read back, and their exact dX/dp is the central difference's.
Usage: python3 test_vtk_pipeline.py PLUGIN_FILE EXAMPLES_OPENFOAM_DIR WORK_DIR"""
import os
import subprocess
import sys

plugin, examples, work = sys.argv[1:4]
folder = os.path.dirname(os.path.abspath(plugin))
sys.path.insert(0, folder)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mlsdeform  # noqa: E402
from mlsdeform import vtkfoam  # noqa: E402

from checks import check, finish, raises  # noqa: E402

case = os.path.join(work, 'case')
subprocess.run(['bash', os.path.join(examples, 'make-case.sh'), case], check=True)
# open_case's default (polyhedra kept as OpenFOAM's cells), as morph_case.py reads the case
handle, fixed, slip = ['body'], ['inlet', 'outlet'], ['ground', 'top', 'front', 'back']
reader = vtkfoam.open_case(os.path.join(case, 'case.foam'), handle + fixed + slip)
deform = vtkfoam.morph(reader, handle, (0.05, 0, 0.02), fixed, slip)
vtkfoam.save_variant(deform, os.path.join(work, 'vtk-variant', 'case.foam'), link=True)
check('paraview.servermanager' not in sys.modules and 'paraview.simple' not in sys.modules,
      "the pipeline ran without ParaView's server manager")
polymesh = os.path.join(work, 'vtk-variant', 'constant', 'polyMesh')
check(os.path.isfile(os.path.join(polymesh, 'points')) and not os.path.islink(os.path.join(polymesh, 'points')),
      'the variant holds its own points file')
check(os.path.islink(os.path.join(polymesh, 'faces')), "and links the source's unchanged faces")

subprocess.run(['pvpython', '--no-mpi', os.path.join(examples, 'morph_case.py'), plugin, os.path.join(case, 'case.foam'),
                os.path.join(work, 'pv-variant')], check=True)
with open(os.path.join(polymesh, 'points'), 'rb') as a, open(os.path.join(work, 'pv-variant', 'constant', 'polyMesh', 'points'), 'rb') as b:
    mine, theirs = a.read(), b.read()
with open(os.path.join(case, 'constant', 'polyMesh', 'points'), 'rb') as source:
    check(mine != source.read(), "the variant's points moved")
check(mine == theirs, "its points file is pvpython's, byte for byte (%d bytes)" % len(mine))

# a target folder that does not exist: refused, nothing written
try:
    vtkfoam.save_variant(deform, os.path.join(work, 'no-such-folder', 'variant', 'case.foam'))
    check(False, 'a variant in a folder that does not exist raises RuntimeError')
except RuntimeError as e:
    check('Nothing was written' in str(e) and not os.path.exists(os.path.join(work, 'no-such-folder')),
          'a variant in a folder that does not exist is refused (%s), and nothing is written' % e)
raises(lambda: vtkfoam.open_case(os.path.join(case, 'case.foam'), ['hull']), 'has no patch or patch group hull', 'a patch the case lacks')
raises(lambda: vtkfoam.open_case(case, ['body']), 'is not a .foam file: name the case\'s .foam file', 'the case folder for its .foam file')
from mlsdeform import meshfile  # noqa: E402
raises(lambda: meshfile.open_mesh(case), 'is a folder: name the mesh file in it', 'a folder for a mesh file')
try:
    mlsdeform.DesignVariables(reader)
    check(False, 'design variables on the reader raise RuntimeError')
except RuntimeError as e:
    check('design variables go on an MLS Deform filter, not on a vtkOpenFOAMReader' in str(e), 'design variables on the reader: %s' % e)
raises(lambda: mlsdeform.DesignVariables(deform).addHandleDV('dx', 'body', translate=[1, 0, 0]), 'not patch or set names',
       'a patch name for a Handle region')
# a newcomer's folder named instead of a .foam file, with overwrite: its folder (the would-be case's
# parent) is not replaced; nor is an existing folder that is no OpenFOAM case
mine = os.path.join(work, 'mine')
os.makedirs(os.path.join(mine, 'old'), exist_ok=True)
with open(os.path.join(mine, 'precious.txt'), 'w') as f:
    f.write('kept')
for target, message in ((os.path.join(mine, 'variantB'), 'is not a .foam file'), (os.path.join(mine, 'case.foam'), 'is not an OpenFOAM case')):
    try:
        vtkfoam.save_variant(deform, target, overwrite=True)
        check(False, 'a variant to %s raises RuntimeError' % target)
    except RuntimeError as e:
        check(message in str(e) and sorted(os.listdir(mine)) == ['old', 'precious.txt'],
              'a variant to %s with overwrite is refused, the folder kept (%s)' % (target, e))

# design variables on the VTK filter: written to the region, read back by a new DesignVariables,
# exact derivatives against central differences (as test_design_variables.py: translation acts
# linearly, so the difference is exact up to the output's round-off, 1e-14 over the step 1e-4;
# the rotation's truncation is (h pi/180)^2 / 6 = 5e-13)
body = deform.GetInputAlgorithm(1, 0)
dvs = mlsdeform.DesignVariables(deform)
dvs.addHandleDV('dx', body, translate=[1, 0, 0], lower=-0.05, upper=0.05)
dvs.addHandleDV('yaw', body, rotate=[0, 0, 1], lower=-10, upper=10, value=2.0)
check(body.GetNumberOfDesignVariables() == 2, 'the variables are rows of the vtkConstraintRegion')
again = mlsdeform.DesignVariables(deform)
check(again.getVarNames() == ['dx', 'yaw'] and again.getValues() == {'dx': 0.0, 'yaw': 2.0}
      and again.getBounds() == {'dx': (-0.05, 0.05), 'yaw': (-10.0, 10.0)},
      'a new DesignVariables reads them back from the region (%s)' % again.getValues())
raises(lambda: dvs.addHandleDV('fix', deform.GetInputAlgorithm(1, 1), translate=[1, 0, 0]), 'Handle', 'a variable on a Fixed region')
worst = dvs.checkDerivatives(step=1e-4, verbose=False)
check(worst <= 1e-6, "dX/dp of the VTK filter's variables is the central difference's (%.2e)" % worst)
finish()
