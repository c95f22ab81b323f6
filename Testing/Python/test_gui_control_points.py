"""Run inside the paraview GUI (paraview --dr --script=test_gui_control_points.py): issue 66 point
1, local shape variables in the GUI. The sphere in a box (sphere_in_box.local_scene: 12 control
points on the sphere along its outward normals) shown: the sphere's Handle draws its control points
as arrows along their directions (3D Glyphs oriented by ControlDirection, a twentieth of the
model's size), a region without control points stays drawn as points; with ComputeSensitivities
the deformed model is coloured by one local variable's |dX/dp|, which is 1 at its control point
(it moves by exactly p along the unit normal) and the legend spans the data. Writes the window's
picture as MLSDEFORM_SCREENSHOT when set, and 'ok' or the failures to MLSDEFORM_GUI_RESULT."""
import os

from checks import check, write_result  # Testing/Python, on PYTHONPATH


try:
    from PyQt5.QtWidgets import QApplication
    import paraview.simple as pvs
    from paraview import servermanager as sm
    pvs.LoadPlugin(os.environ['MLSDEFORM_PLUGIN'], remote=False, ns=globals())
    import numpy as np
    import sphere_in_box
    app = QApplication.instance()

    def settle():
        for _ in range(10):
            app.processEvents()

    work = os.path.dirname(os.environ['MLSDEFORM_GUI_RESULT'])
    path = os.path.join(work, 'control-points-scene.vtm')
    sphere_in_box.write_scene(path, 6)
    source = pvs.OpenDataFile(path)
    deform, dvs, bumps, pair, (body, fixed, floor, side) = sphere_in_box.local_scene(globals(), source)
    view = pvs.GetActiveViewOrCreate('RenderView')
    for region in (body, fixed):
        pvs.Show(region, view)
    pvs.Render(view)
    settle()
    arrows = sm.GetRepresentation(body, view)
    check(arrows.Representation == '3D Glyphs' and arrows.GlyphType.GetXMLName() == 'ArrowSource' and
          arrows.Orient == 1 and arrows.SelectOrientationVectors == 'ControlDirection',
          'the control points drawn as arrows along ControlDirection (%s, %s, oriented by %s)' % (
              arrows.Representation, arrows.GlyphType.GetXMLName(), arrows.SelectOrientationVectors))
    check(abs(arrows.ScaleFactor - np.sqrt(12) / 20) <= 1e-9 and arrows.Scaling == 1 and arrows.ScaleByArray == 0, 'the arrows a twentieth of the model (its diagonal 2 sqrt 3): '
          'scale factor %g' % arrows.ScaleFactor)
    points = sm.GetRepresentation(fixed, view)
    check(points.Representation == 'Points', 'a region without control points drawn as points (%s)' % points.Representation)

    # one local variable's dX/dp coloured on the deformed model
    deform.ComputeSensitivities = 1
    shown = pvs.Show(deform, view)
    pvs.ColorBy(shown, ('POINTS', 'dX/dbump_0', 'Magnitude'))
    pvs.Render(view)
    settle()
    array = deform.PointData['dX/dbump_0']
    low, high = array.GetRange(-1)
    check(abs(high - 1) <= 1e-9 and low <= 1e-12, '|dX/dbump_0| from %g to %g: 1 at its control point, 0 where held' % (low, high))
    lut = pvs.GetColorTransferFunction('dXdbump_0')
    values = list(lut.RGBPoints)[0::4]
    check(abs(values[0] - low) <= 1e-6 and abs(values[-1] - high) <= 1e-6, 'the legend spans %g-%g, the data %g-%g' % (
        values[0], values[-1], low, high))
    if os.environ.get('MLSDEFORM_SCREENSHOT'):
        window = [w for w in QApplication.topLevelWidgets() if w.objectName() == 'pqClientMainWindow'][0]
        window.resize(1200, 800)
        # the sphere alone, with its first variable at its upper bound (the bump), coloured by its dX/dp
        dvs.setDesignVars({'bump_0': 0.05})
        pvs.Hide(deform, view)
        pvs.Hide(fixed, view)
        sphere = pvs.Show(pvs.ExtractBlock(Input=deform, Selectors=['/Root/sphere']), view)
        pvs.ColorBy(sphere, ('POINTS', 'dX/dbump_0', 'Magnitude'))
        sphere.SetScalarBarVisibility(view, True)
        x0 = dvs.getControlPoints('bump_0')['bump_0'][0][0]   # looked at from outside its control point
        side = np.cross(x0, [0, 0, 1]) if abs(x0[2]) < 0.9 * np.linalg.norm(x0) else np.array([1.0, 0, 0])
        eye = x0 / np.linalg.norm(x0) + 0.5 * side / np.linalg.norm(side)
        view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = list(1.8 * eye / np.linalg.norm(eye)), [0, 0, 0], [0, 0, 1]
        pvs.Render(view)
        settle()
        window.grab().save(os.environ['MLSDEFORM_SCREENSHOT'])
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    import traceback
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], '%r\n%s' % (error, traceback.format_exc()))
