"""Issue 12 point 1 in the GUI: File > Save Data of an MLS Deform of an OpenFOAM case writes the
variant case, as SaveData does in pvpython. Two runs on a case built by make-case.sh:

    paraview --script=test_gui_save_data.py --test-script=save_data.xml --exit
        builds the pipeline and makes MLS Deform the active source (environment: MLSDEFORM_PLUGIN,
        MLSDEFORM_CASE, and Examples/OpenFOAM on PYTHONPATH in both runs); the recorded events then choose File > Save Data, the file name from the
        test's folder and OK in the writer's settings dialog.
    pvpython test_gui_save_data.py PLUGIN CASE_FOAM GUI_VARIANT_FOAM
        builds the same pipeline, saves it with SaveData and checks that the GUI's variant is the
        same case: every file of the pvpython variant present with the same content (points
        included, so the GUI wrote double points of the same deformation) and checkMesh passes.
"""
import filecmp
import os
import subprocess
import sys

import paraview.simple as pvs

in_gui = 'MLSDEFORM_CASE' in os.environ
plugin, case = (os.environ['MLSDEFORM_PLUGIN'], os.environ['MLSDEFORM_CASE']) if in_gui else sys.argv[1:3]
pvs.LoadPlugin(plugin, remote=False)
import openfoam_variant  # noqa: E402 (Examples/OpenFOAM, on PYTHONPATH)

# The round-trip test's motion: the body (a sphere) moves, inlet and outlet stay, the tunnel walls slide.
handle, fixed, slip = ['body'], ['inlet', 'outlet'], ['ground', 'top', 'front', 'back']
reader = openfoam_variant.open_case(case, handle + fixed + slip)
deformed = openfoam_variant.morph(reader, handle, [0.05, 0.0, 0.02], fixed, slip)
if in_gui:
    pvs.Show(deformed)
    pvs.Render()
    pvs.SetActiveSource(deformed)
else:
    gui_variant = os.path.dirname(sys.argv[3])
    reference = os.path.join(os.path.dirname(gui_variant), 'pvpython-variant')
    openfoam_variant.save_variant(deformed, os.path.join(reference, 'case.foam'), overwrite=True)
    failures = []
    for folder, _, files in os.walk(reference):
        for name in files:
            path = os.path.join(folder, name)
            twin = os.path.join(gui_variant, os.path.relpath(path, reference))
            if not os.path.isfile(twin) or not filecmp.cmp(path, twin, shallow=False):
                failures.append('the GUI variant lacks or differs in ' + os.path.relpath(path, reference))
    check = subprocess.run(['bash', '-c', 'source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1; checkMesh -case "%s"' % gui_variant],
                           capture_output=True, text=True).stdout
    if 'Mesh OK.' not in check:
        failures.append('checkMesh of the GUI variant:\n' + check[-2000:])
    print('\n'.join(failures) or 'ok: the GUI variant equals the pvpython variant and checkMesh passes')
    sys.exit(1 if failures else 0)
