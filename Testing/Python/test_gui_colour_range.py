"""Run inside the paraview GUI (paraview --dr --script=test_gui_colour_range.py): issue 32, point 4,
and issue 54, point 5. The deformed fandisk's Displacement legend shows the current range after
each update: a zero motion as 0 to 1% of the part's diagonal (not ParaView's 0 to 1.2e-38 of an
empty range), a large motion up to its largest displacement, a smaller one after it up to its own
(the range shrinks, it does not keep the largest seen), and a range the user locked stays. The
same for a legend of dX/d<variable> when the variable's axis shrinks, and for an Extract Block
downstream of a deformed multiblock, coloured by Displacement. The colouring menu lists no
field-data report array. Writes 'ok' or the failures to the file named by MLSDEFORM_GUI_RESULT."""
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
    # and after ParaView's own rescales of that legend: another component, colouring anew, Reset Range
    from paraview.simple import ColorBy, GetDisplayProperties
    look = GetDisplayProperties(deformed)
    for action, what in ((lambda: ColorBy(look, ('POINTS', 'Displacement', 'X')), 'the X component'),
                         (lambda: (ColorBy(look, None), ColorBy(look, ('POINTS', 'Displacement', 'Magnitude'))), 'colouring anew'),
                         (lambda: look.RescaleTransferFunctionToDataRange(False, True), 'Reset Range')):
        action()
        Render()
        low, high = legend()
        check(low == 0 and abs(high - 0.01 * diagonal) <= 1e-12 * diagonal,
              'zero motion, after %s: legend %g to %g, not 0 to %g' % (what, low, high, 0.01 * diagonal))
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
    lut.AutomaticRescaleRangeMode = 'Grow and update on \'Apply\''

    # the colouring menu: the deformed model's arrays, none of its field-data reports
    from paraview.simple import ColorBy, ExtractBlock, GetDisplayProperties, GroupDatasets, Hide, SetActiveSource
    look = GetDisplayProperties(deformed)
    domain = look.GetProperty('ColorArrayName').SMProperty.GetDomain('array_list')
    listed = [domain.GetString(i) for i in range(domain.GetNumberOfStrings())]
    reports = [deformed.GetDataInformation().GetFieldDataInformation().GetArrayInformation(i).GetName()
               for i in range(deformed.GetDataInformation().GetFieldDataInformation().GetNumberOfArrays())]
    check(len(reports) > 5 and not set(reports) & set(listed) and 'Displacement' in listed,
          'the colouring menu lists %s, none of the %d report arrays %s' % (listed, len(reports), reports))

    # dX/dlift: its legend follows when the variable's axis shrinks (|dX/dlift| is the axis's
    # length on the handle: 1.7, then 1)
    handle.DesignVariables = ['lift', '0', '0', '0', '1.7', '0', '-1', '1']
    deformed.ComputeSensitivities = 1
    Render()
    ColorBy(look, ('POINTS', 'dX/dlift', 'Magnitude'))
    Render()
    sensitivity = GetColorTransferFunction('dX/dlift')
    for axis in (1.7, 1.0):
        handle.DesignVariables = ['lift', '0', '0', '0', str(axis), '0', '-1', '1']
        Render()
        top = deformed.GetDataInformation().GetPointDataInformation().GetArrayInformation('dX/dlift').GetComponentRange(-1)[1]
        points = sensitivity.RGBPoints
        check(abs(top - axis) <= 0.01 * axis and abs(points[-4] - top) <= 1e-6 * top,
              'dX/dlift along %g z: legend up to %g, |dX/dlift| up to %g' % (axis, points[-4], top))
    ColorBy(look, ('POINTS', 'Displacement', 'Magnitude'))

    # downstream: an Extract Block of a deformed multiblock, coloured by Displacement
    Hide(deformed)
    group = GroupDatasets(Input=[part])
    blocks = MLSDeform(Input=group, Regions=[fixed, handle], NumberOfSamples=500)  # noqa: F821
    block = ExtractBlock(Input=blocks, Selectors=['/Root/*'])
    shown = Show(block)
    ColorBy(shown, ('POINTS', 'Displacement', 'Magnitude'))
    SetActiveSource(block)
    for motion in (0.0, 0.1, 0.02):
        handle.Translation = [-motion * height, 0.0, 0.0]
        Render()
        low, high = legend()
        moved = block.GetDataInformation().GetPointDataInformation().GetArrayInformation('Displacement').GetComponentRange(-1)[1]
        expected = moved if motion else 0.01 * diagonal
        check(low == 0 and abs(high - expected) <= 1e-6 * expected,
              'Extract Block downstream, motion %g of the height: legend %g to %g, expected 0 to %g' % (motion, low, high, expected))

    # after a state file: the loaded representations' legends follow too
    import tempfile
    from paraview.simple import FindSource, GetSources, LoadState, ResetSession, SaveState
    state = os.path.join(tempfile.mkdtemp(), 'legends.pvsm')
    names = {proxy: name for (name, _), proxy in GetSources().items()}
    SaveState(state)
    ResetSession()
    LoadPlugin(os.environ['MLSDEFORM_PLUGIN'], remote=False, ns=globals())
    LoadState(state, data_directory=os.environ['MLSDEFORM_DATA_DIR'])
    block, handle = FindSource(names[block]), FindSource(names[handle])
    lut = GetColorTransferFunction('Displacement')
    for motion in (0.12, 0.04):
        handle.Translation = [-motion * height, 0.0, 0.0]
        Render()
        low, high = legend()
        moved = block.GetDataInformation().GetPointDataInformation().GetArrayInformation('Displacement').GetComponentRange(-1)[1]
        check(low == 0 and abs(high - moved) <= 1e-6 * moved,
              'after Load State, motion %g of the height: legend %g to %g, expected 0 to %g' % (motion, low, high, moved))
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], error)
