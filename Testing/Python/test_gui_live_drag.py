"""Run inside the paraview GUI (paraview --dr --script=test_gui_live_drag.py): issue 32, point 7.
A model of a volume block (a tetrahedralized grid) and its surface block, as an OpenFOAM case's
internal mesh and patches. With Auto Apply on, the Handle's box is dragged up in motion events,
as vtkBoxWidget2 reports a drag (start, moves, end). While the drag goes on, the region's Dragging
is on and each applied step moves the surface block only: the volume block keeps its displacement
of before the drag (zero). On release Dragging goes off and the volume block follows with no new
set-up: its largest displacement is then the surface's, and Undo leaves Dragging off.
Writes 'ok' or the failures to MLSDEFORM_GUI_RESULT."""
import os

import checks  # Testing/Python, on PYTHONPATH
from checks import check, write_result

STEPS = 3

try:
    from PyQt5.QtWidgets import QAction, QApplication
    import paraview.simple as pvs
    from paraview.modules.vtkRemotingSettings import vtkPVGeneralSettings
    from paraview.vtk import vtkTransform
    import fandisk_scene as scene  # Examples/, on PYTHONPATH

    scene.load_plugin(os.environ['MLSDEFORM_PLUGIN'])
    app = QApplication.instance()

    def settle(until=lambda: False, seconds=10.0):
        checks.settle(app, until, seconds)

    def largest_displacement(block):
        """The largest displacement magnitude in one block of the deformed output (0 volume, 1 surface)."""
        # the filter's own output (the GUI's built-in server): no proxy is made, none enters the undo stack
        data = deformed.GetClientSideObject().GetOutputDataObject(0).GetBlock(block)
        array = data.GetPointData().GetArray('Displacement')
        return array.GetRange(-1)[1]

    grid = pvs.Wavelet(WholeExtent=[-4, 4, -4, 4, -4, 4])
    volume = pvs.Tetrahedralize(Input=grid)
    surface = pvs.ExtractSurface(Input=volume)
    model = pvs.GroupDatasets(Input=[volume, surface])
    model.UpdatePipeline()
    fixed = scene.box_region(model, 'Fixed', [-5, -5, -4.5], [5, 5, -3.5])
    handle = scene.box_region(model, 'Handle', [-5, -5, 3.5], [5, 5, 4.5])
    deformed = scene.MLSDeform(Input=model, Regions=[fixed, handle], NumberOfSamples=300)
    view = pvs.GetActiveViewOrCreate('RenderView')
    pvs.Show(deformed, view)
    pvs.SetActiveSource(handle)
    pvs.Render(view)
    settle(seconds=0.5)
    boxes = [p.SMProxy for p in view.GetProperty('HiddenRepresentations')
             if p.SMProxy.GetXMLName().endswith('BoxWidgetRepresentation') and p.SMProxy.GetProperty('Visibility').GetElement(0)
             and (p.SMProxy.GetLogName() or '').startswith('handle motion box of ')]
    if len(boxes) != 1:
        raise RuntimeError('expected one handle box, found %d' % len(boxes))
    widget = boxes[0]
    representation = widget.GetRepresentationProxy().GetClientSideObject()
    check(largest_displacement(0) == 0 and largest_displacement(1) == 0, 'no displacement before the drag')

    settings = vtkPVGeneralSettings.GetInstance()
    auto_apply = settings.GetAutoApply()
    settings.SetAutoApply(True)
    start = vtkTransform()
    representation.GetTransform(start)
    widget.GetWidget().InvokeEvent('StartInteractionEvent')
    step = 0.2
    for k in range(1, STEPS + 1):
        moved = vtkTransform()
        moved.PostMultiply()
        moved.Concatenate(start)
        moved.Translate(0, 0, k * step)
        representation.SetTransform(moved)
        widget.GetWidget().InvokeEvent('InteractionEvent')
        settle(lambda: abs(handle.Translation[2] - k * step) < 1e-9)
        pvs.Render(view)
        check(handle.Dragging == 1, 'motion event %d: the region is Dragging' % k)
        surface_moved, volume_moved = largest_displacement(1), largest_displacement(0)
        # the top moves by the translation: the surface's largest displacement is k step (to the
        # solve's target residual, ~1e-3 of it with the default weights); the volume stays
        check(abs(surface_moved - k * step) < 0.05 * k * step and volume_moved == 0,
              'motion event %d applied to the surface only: largest displacement %.4g on the surface (%.4g expected), '
              '%.4g in the volume (0 expected)' % (k, surface_moved, k * step, volume_moved))
    widget.GetWidget().InvokeEvent('EndInteractionEvent')
    settle(lambda: handle.Dragging == 0 and largest_displacement(0) > 0, seconds=10.0)
    check(handle.Dragging == 0, 'released: the region is no longer Dragging')
    surface_moved, volume_moved = largest_displacement(1), largest_displacement(0)
    dragged = STEPS * step
    check(abs(volume_moved - dragged) < 0.05 * dragged and abs(surface_moved - dragged) < 0.05 * dragged,
          'released: the volume follows, largest displacement %.4g in the volume and %.4g on the surface (%.4g expected)'
          % (volume_moved, surface_moved, dragged))
    resampled = deformed.GetDataInformation().GetFieldDataInformation().GetArrayInformation('Resampled')
    check(resampled is not None and resampled.GetComponentRange(0)[1] == 0, 'no new set-up on release (Resampled 0)')

    undo = [a for w in app.topLevelWidgets() if w.objectName() == 'pqClientMainWindow'
            for a in w.findChildren(QAction) if a.objectName() == 'actionEditUndo'][0]
    undo.trigger()
    settle(lambda: abs(handle.Translation[2]) < 1e-9)
    check(abs(handle.Translation[2]) < 1e-9 and handle.Dragging == 0, 'one Undo returns the handle (Translation %s) '
          'and leaves Dragging off (%d)' % (list(handle.Translation), handle.Dragging))
    settings.SetAutoApply(auto_apply)
    write_result(os.environ['MLSDEFORM_GUI_RESULT'])
except Exception as error:  # reported through the result file, the GUI swallows exceptions
    write_result(os.environ['MLSDEFORM_GUI_RESULT'], error)
