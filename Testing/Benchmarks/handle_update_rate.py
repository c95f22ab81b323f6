"""How many handle motions per second the fandisk follows (issue 13: dragging the handle with
Auto Apply on updates the deformed model continuously; target >= 10 per second). Each update is
what a drag step costs after Apply: the Constraint Region's new motion, MLS Deform's re-solve on
its cached set-up, and a render of the deformed model (coloured by displacement magnitude) with
the handle's points, offscreen at 800x600. Prints the set-up time and the median and 90th
percentile time per update over a sweep of motions.

    pvpython --no-mpi handle_update_rate.py PLUGIN FANDISK.off [UPDATES]
"""
import os
import statistics
import sys
import time

import paraview.simple as pvs

plugin, mesh = sys.argv[1:3]
updates = int(sys.argv[3]) if len(sys.argv) > 3 else 60
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'Examples'))
import fandisk_scene as scene  # noqa: E402

scene.load_plugin(plugin)
part = pvs.OpenDataFile(mesh)
part.UpdatePipeline()
bounds = part.GetDataInformation().GetBounds()
height = bounds[5] - bounds[4]
fixed, handle = scene.fixed_and_handle(part, bounds)  # the scene of Examples/ and the GUI test
deformed = scene.MLSDeform(Input=part, Regions=[fixed, handle])
view = pvs.CreateRenderView()
view.ViewSize = [800, 600]
display = pvs.Show(deformed, view)
pvs.ColorBy(display, ('POINTS', 'Displacement', 'Magnitude'))
pvs.Show(handle, view)
start = time.perf_counter()
pvs.Render(view)
setup = time.perf_counter() - start

times = []
for i in range(updates):
    step = (i + 1) / updates
    handle.Translation = [0.05 * height * step, 0.0, 0.1 * height * step]
    handle.Rotation = [0.0, 0.0, 20.0 * step]
    start = time.perf_counter()
    pvs.Render(view)
    times.append(time.perf_counter() - start)
times.sort()
median = statistics.median(times)
print('fandisk: %d points; set-up (first update) %.2f s; per update over %d motions: median %.1f ms, '
      '90th percentile %.1f ms; %.0f updates per second (target >= 10)'
      % (part.GetDataInformation().GetNumberOfPoints(), setup, updates, 1e3 * median,
         1e3 * times[int(0.9 * (len(times) - 1))], 1 / median))
