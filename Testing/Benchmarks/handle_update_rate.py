"""How many handle motions per second the view follows while a handle is dragged (issue 13: the
fandisk, target >= 10 per second; issue 32, point 7: the 1M-cell OpenFOAM case, target >= 5).
Each update is what a drag step costs after Apply: the Constraint Region's new motion, MLS
Deform's re-solve on its cached set-up, and a render, offscreen at 800x600. Prints the set-up
time and the median and 90th percentile time per update over a sweep of motions.

    pvpython --no-mpi handle_update_rate.py PLUGIN FANDISK.off [UPDATES]
    pvpython --no-mpi handle_update_rate.py PLUGIN CASE.foam [UPDATES]

The fandisk is rendered coloured by displacement magnitude with the handle's points. On an
OpenFOAM case (the benchmarks' hull in a box: hull moved, inlet and outlet fixed, sides, bottom
and top slipping) the view shows the hull patch coloured by displacement magnitude, the internal
mesh hidden, and the drag runs as the GUI's handle box runs it: the region's Dragging on, so
that a step moves the patches only; the release (Dragging off) moves the internal mesh, timed
apart. The same steps without Dragging, each moving the whole mesh, are timed for comparison.
"""
import os
import statistics
import sys
import time

import paraview.simple as pvs

plugin, mesh = sys.argv[1:3]
updates = int(sys.argv[3]) if len(sys.argv) > 3 else 60
examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'Examples')
sys.path.insert(0, examples)
import fandisk_scene as scene  # noqa: E402

scene.load_plugin(plugin)


def timed_updates(view, handle, translation, degrees, count):
    """Seconds per render of count handle motions sweeping to the translation and a rotation by
    degrees about z, sorted."""
    times = []
    for i in range(count):
        step = (i + 1) / count
        handle.Translation = [step * t for t in translation]
        handle.Rotation = [0.0, 0.0, degrees * step]
        start = time.perf_counter()
        pvs.Render(view)
        times.append(time.perf_counter() - start)
    return sorted(times)


def figures(times):
    median = statistics.median(times)
    return 'median %.1f ms, 90th percentile %.1f ms; %.1f updates per second' % (
        1e3 * median, 1e3 * times[int(0.9 * (len(times) - 1))], 1 / median)


view = pvs.CreateRenderView()
view.ViewSize = [800, 600]
if mesh.endswith('.foam'):
    pvs.LoadPlugin(plugin, remote=False)  # its proxies into paraview.simple, where mlsdeform.foam finds them
    sys.path.insert(0, os.path.join(examples, 'OpenFOAM'))
    import openfoam_variant  # noqa: E402
    hull, fixed, slip = ['hull'], ['inlet', 'outlet'], ['sideYmin', 'sideYmax', 'bottom', 'top']
    reader = openfoam_variant.open_case(mesh, hull + fixed + slip, decompose_polyhedra=False)
    info = reader.GetDataInformation()
    start = time.perf_counter()
    deformed = openfoam_variant.morph(reader, hull, [0.0, 0.0, 0.0], fixed, slip)
    shown = pvs.ExtractBlock(Input=deformed, Selectors=['/Root/boundary/hull'])
    display = pvs.Show(shown, view)
    pvs.ColorBy(display, ('POINTS', 'Displacement', 'Magnitude'))
    view.ResetCamera()
    pvs.Render(view)
    setup = time.perf_counter() - start
    handle = deformed.Regions[0]
    motion = [0.25, 0.0, 0.1], 2.0  # [m], degrees: as run-openfoam-benchmark.sh's motion, and a turn
    name = '%s (%d points, %d cells)' % (os.path.basename(os.path.dirname(os.path.abspath(mesh))),
                                         info.GetNumberOfPoints(), info.GetNumberOfCells())
    handle.Dragging = 1
    dragged = timed_updates(view, handle, *motion, updates)
    handle.Dragging = 0
    start = time.perf_counter()
    pvs.Render(view)
    release = time.perf_counter() - start
    inverted = deformed.GetDataInformation().GetFieldDataInformation().GetArrayInformation('InvertedCells')
    # the same motions again, each moving the whole mesh (what a drag step cost before)
    handle.Translation, handle.Rotation = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    pvs.Render(view)
    whole = timed_updates(view, handle, *motion, max(3, updates // 10))
    print('%s: set-up (first update) %.2f s; per drag step (surface) over %d motions: %s (target >= 5); '
          'release (the internal mesh follows) %.2f s, %s inverted cells; a step moving the whole mesh: %s'
          % (name, setup, updates, figures(dragged), release,
             'no' if inverted is None else '%d' % inverted.GetComponentRange(0)[0], figures(whole)))
else:
    part = pvs.OpenDataFile(mesh)
    part.UpdatePipeline()
    bounds = part.GetDataInformation().GetBounds()
    fixed, handle = scene.fixed_and_handle(part, bounds)  # the scene of Examples/ and the GUI test
    deformed = scene.MLSDeform(Input=part, Regions=[fixed, handle])
    display = pvs.Show(deformed, view)
    pvs.ColorBy(display, ('POINTS', 'Displacement', 'Magnitude'))
    pvs.Show(handle, view)
    start = time.perf_counter()
    pvs.Render(view)
    setup = time.perf_counter() - start
    height = bounds[5] - bounds[4]
    times = timed_updates(view, handle, [0.05 * height, 0.0, 0.1 * height], 20.0, updates)
    print('fandisk: %d points; set-up (first update) %.2f s; per update over %d motions: %s (target >= 10)'
          % (part.GetDataInformation().GetNumberOfPoints(), setup, updates, figures(times)))
