"""A deformation recovers after any number of failed updates, and a failure is detectable from a
script: the sequence a user makes in the GUI (only a Fixed region: error; the Fixed box edited:
error again; a Handle added: the view shows the deformed part), replayed with Render() only,
never an explicit UpdatePipeline(), then broken and fixed once more.

    pvpython test_recovery.py PLUGIN DATA_DIR
    paraview --script=test_recovery.py   (PLUGIN, DATA_DIR and the result file from the
                                          environment: MLSDEFORM_PLUGIN, MLSDEFORM_DATA_DIR,
                                          MLSDEFORM_GUI_RESULT; the GUI swallows exceptions)
"""
import os
import sys

from paraview.simple import GetActiveViewOrCreate, GetRepresentation, LoadPlugin, OpenDataFile, Render, Show

in_gui = 'MLSDEFORM_GUI_RESULT' in os.environ
plugin, data_dir = (os.environ['MLSDEFORM_PLUGIN'], os.environ['MLSDEFORM_DATA_DIR']) if in_gui else sys.argv[1:3]
failures = []


def check(condition, what):
    print(('ok   ' if condition else 'FAIL ') + what)
    if not condition:
        failures.append(what)


def shown(deformed, view):
    """What the view shows of the deformation: (has a Displacement array, error message or None,
    bounds), from the representation's data, which is what Render() updated."""
    info = GetRepresentation(deformed, view).GetRepresentedDataInformation()
    error = info.GetFieldDataInformation().GetArrayInformation('DeformationError')
    displacement = info.GetPointDataInformation().GetArrayInformation('Displacement')
    return displacement is not None, error.GetStringValue(0) if error else None, info.GetBounds()


def replay():
    LoadPlugin(plugin, remote=False, ns=globals())
    part = OpenDataFile(data_dir + '/fandisk.off')
    part.UpdatePipeline()
    bounds = part.GetDataInformation().GetBounds()
    zmin, zmax = bounds[4], bounds[5]
    height = zmax - zmin
    fixed = ConstraintRegion(Input=part, Role='Fixed')  # noqa: F821 (from the plugin)
    fixed.Region = 'Box'
    fixed.Region.Position = [bounds[0] - 1, bounds[2] - 1, zmin - 0.01 * height]
    fixed.Region.Length = [bounds[1] - bounds[0] + 2, bounds[3] - bounds[2] + 2, 0.11 * height]
    deformed = MLSDeform(Input=part, Regions=[fixed])  # noqa: F821
    view = GetActiveViewOrCreate('RenderView')
    Show(deformed, view)

    for attempt in range(3):  # any number of failures: three, each after an edit
        fixed.Region.Length = [bounds[1] - bounds[0] + 2, bounds[3] - bounds[2] + 2, (0.11 + 0.01 * attempt) * height]
        Render(view)
        has_displacement, error, shown_bounds = shown(deformed, view)
        check(error is not None and 'Handle' in error, 'failure %d: the output carries DeformationError (%s)' % (attempt + 1, error))
        check(not has_displacement and shown_bounds == bounds, 'failure %d: the view shows the unchanged input' % (attempt + 1))

    handle = ConstraintRegion(Input=part, Role='Handle', Translation=[-0.15 * height, 0, 0])  # noqa: F821
    handle.Region = 'Box'
    handle.Region.Position = [bounds[0] - 1, bounds[2] - 1, zmax - 0.25 * height]
    handle.Region.Length = [bounds[1] - bounds[0] + 2, bounds[3] - bounds[2] + 2, 0.26 * height]
    deformed.Regions = [fixed, handle]
    Render(view)
    has_displacement, error, shown_bounds = shown(deformed, view)
    check(error is None and has_displacement, 'fixed: the view shows the deformation (error %s)' % error)
    # the top quarter moves by -0.15 height along x: the lower x bound moves by most of that
    check(shown_bounds[0] < bounds[0] - 0.1 * height, 'fixed: the view shows the moved part (xmin %.4g -> %.4g)' % (bounds[0], shown_bounds[0]))

    fixed.Region.Length = [0, 0, 0]  # a region that selects nothing: an error
    Render(view)
    check(shown(deformed, view)[1] is not None, 'an empty Fixed region: an error again')
    fixed.Region.Length = [bounds[1] - bounds[0] + 2, bounds[3] - bounds[2] + 2, 0.11 * height]
    Render(view)
    has_displacement, error, _ = shown(deformed, view)
    check(error is None and has_displacement, 'fixed again: the view shows the deformation')


try:
    replay()
    message = 'ok' if not failures else 'failed: ' + '; '.join(failures)
except Exception as error:  # noqa: BLE001 (reported, the GUI swallows exceptions)
    message = 'error: %s' % error
print(message)
if in_gui:
    with open(os.environ['MLSDEFORM_GUI_RESULT'], 'w') as f:
        f.write(message)
elif message != 'ok':
    sys.exit(1)  # (not on success: sys.exit while a render window lives ends in an X error, exit code 1)
