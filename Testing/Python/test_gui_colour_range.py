"""Run inside the paraview GUI (paraview --dr --script=test_gui_colour_range.py): issue 32, point 4.
The deformed fandisk's Displacement legend shows the current range after each update: a zero
motion as 0 to 1% of the part's diagonal (not ParaView's 0 to 1.2e-38 of an empty range), a
large motion up to its largest displacement, a smaller one after it up to its own (the range
shrinks, it does not keep the largest seen), and a range the user locked stays.
Writes 'ok' or the failures to the file named by MLSDEFORM_GUI_RESULT."""
import math
import os

from checks import check, write_result  # Testing/Python, on PYTHONPATH


try:
    from paraview import servermanager
    from paraview.simple import GetColorTransferFunction, LoadPlugin, OpenDataFile, Render, Show
    LoadPlugin(os.environ['MLSDEFORM_PLUGIN'], remote=False, ns=globals())
    part = OpenDataFile(os.path.join(os.environ['MLSDEFORM_DATA_DIR'], 'fandisk.off'))
    part.UpdatePipeline()
    xmin, xmax, ymin, ymax, zmin, zmax = part.GetDataInformation().GetBounds()
    diagonal = math.sqrt((xmax - xmin) ** 2 + (ymax - ymin) ** 2 + (zmax - zmin) ** 2)
    height, margin = zmax - zmin, 0.01 * (zmax - zmin)

    def region(role, zlow, zhigh, **properties):
        r = ConstraintRegion(Input=part, Role=role, **properties)  # noqa: F821 (from the plugin)
        r.Region = 'Box'
        r.Region.Position = [xmin - margin, ymin - margin, zlow]
        r.Region.Length = [xmax - xmin + 2 * margin, ymax - ymin + 2 * margin, zhigh - zlow]
        return r

    fixed = region('Fixed', zmin - margin, zmin + 0.1 * height)
    handle = region('Handle', zmax - 0.25 * height, zmax + margin, Translation=[0.0, 0.0, 0.0])
    deformed = MLSDeform(Input=part, Regions=[fixed, handle], NumberOfSamples=500)  # noqa: F821
    Show(deformed)
    Render()
    lut = GetColorTransferFunction('Displacement')

    def legend():
        points = lut.RGBPoints
        return points[0], points[-4]

    def largest():
        return deformed.GetDataInformation().GetPointDataInformation().GetArrayInformation('Displacement').GetComponentRange(-1)[1]

    # a zero motion: every displacement is 0, the legend 0 to 1% of the diagonal
    check(largest() == 0, 'zero motion: largest displacement %g, not 0' % largest())
    low, high = legend()
    check(low == 0 and abs(high - 0.01 * diagonal) <= 1e-12 * diagonal,
          'zero motion: legend %g to %g, not 0 to %g (1%% of the diagonal)' % (low, high, 0.01 * diagonal))
    # a large motion, then a smaller one: the legend follows the current largest displacement
    # (bounds: the array information's range is exact; 1e-6 relative covers its float output)
    for motion in (0.15, 0.03):
        handle.Translation = [-motion * height, 0.0, 0.0]
        Render()
        low, high = legend()
        check(largest() > 0 and low == 0 and abs(high - largest()) <= 1e-6 * largest(),
              'motion %g of the height: legend %g to %g, largest displacement %g' % (motion, low, high, largest()))
    # locked by the user: the range stays
    lut.AutomaticRescaleRangeMode = 'Never'
    locked = legend()
    handle.Translation = [-0.1 * height, 0.0, 0.0]
    Render()
    check(legend() == locked, 'locked legend %s changed to %s' % (locked, legend()))
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], error)
