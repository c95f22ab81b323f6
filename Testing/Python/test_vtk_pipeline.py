"""A plain VTK pipeline in python3, without ParaView's server manager: ParaView's VTK modules and
the plugin's wrapped filters and case writer (Examples/OpenFOAM/vtk_variant.py) read the
sphereChannel case (built here), deform it (the sphere moved by (0.05, 0, 0.02), inlet and outlet
Fixed, the other planes Slip) and write a linked variant case. The variant's points file must be,
byte for byte, the one pvpython writes through mlsdeform.foam (Examples/OpenFOAM/morph_case.py with
its defaults); a bad target is refused with nothing written.
Usage: python3 test_vtk_pipeline.py PLUGIN_FILE EXAMPLES_OPENFOAM_DIR WORK_DIR"""
import os
import subprocess
import sys

plugin, examples, work = sys.argv[1:4]
folder = os.path.dirname(os.path.abspath(plugin))
sys.path.insert(0, examples)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vtk_variant  # noqa: E402

from checks import check, finish  # noqa: E402

case = os.path.join(work, 'case')
subprocess.run(['bash', os.path.join(examples, 'make-case.sh'), case], check=True)
# Decompose polyhedra on: ParaView's default, as morph_case.py reads the case
_, deform, _ = vtk_variant.morph(folder, os.path.join(case, 'case.foam'), ['body'], (0.05, 0, 0.02), ['inlet', 'outlet'],
                                 ['ground', 'top', 'front', 'back'], decompose_polyhedra=True)
writer = vtk_variant.save_variant(folder, deform, os.path.join(work, 'vtk-variant', 'case.foam'))
check(writer.GetErrorCode() == 0, 'the VTK pipeline writes the variant case')
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
bad = vtk_variant.save_variant(folder, deform, os.path.join(work, 'no-such-folder', 'variant', 'case.foam'))
check(bad.GetErrorCode() != 0 and not os.path.exists(os.path.join(work, 'no-such-folder')),
      'a variant in a folder that does not exist is refused, and nothing is written')
finish()
