"""The structural deck benchmark's runs in one process (run-deck-benchmark.sh): on the plate deck's
mesh (C3D10, Gmsh), the Mesh File reader against meshio reading the same file, the variant writer
against meshio writing the same mesh with moved nodes, and a further variant of the deck (a design
variable set, MLS Deform's update with its FEM verdict, the variant deck written), each the median
of RUNS runs. Prints one JSON line (DECKBENCHMARK {...}).

    python3 deck_benchmark.py PLUGIN_FOLDER DECK RUNS OUT_FOLDER
"""
import json
import os
import statistics
import sys
import time

plugin_folder, deck, runs, out = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
sys.path.insert(0, plugin_folder)
import numpy as np  # noqa: E402
import meshio  # noqa: E402
import mlsdeform  # noqa: E402
from mlsdeform import meshfile, vtkfoam  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

mesh_file = os.path.join(os.path.dirname(deck), 'mesh.inp')
os.makedirs(out, exist_ok=True)


def median_seconds(run):
    times = []
    for _ in range(runs):
        began = time.perf_counter()
        run()
        times.append(time.perf_counter() - began)
    return statistics.median(times)


figures = {'threads': int(os.environ.get('OMP_NUM_THREADS', '0')), 'runs': runs}
reader = meshfile.open_mesh(mesh_file)
grid = reader.GetOutput()
figures['nodes'], figures['elements'] = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
figures['read'] = median_seconds(lambda: meshfile.open_mesh(mesh_file))
figures['meshio_read'] = median_seconds(lambda: meshio.read(mesh_file, file_format='abaqus'))

# the same moved nodes written by both: a smooth shift that changes every coordinate
points = vtk_to_numpy(grid.GetPoints().GetData())
moved = points + 1e-3 * np.sin(points[:, [1, 2, 0]])
shifted = grid.NewInstance()
shifted.ShallowCopy(grid)
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
new_points = vtkPoints()
new_points.SetData(numpy_to_vtk(moved, deep=True))
shifted.SetPoints(new_points)
writer = mlsdeform.deformer._load_wrapping(readers=True).vtkMeshVariantWriter()
writer.SetInputData(shifted)
writer.SetFileName(os.path.join(out, 'variant', 'mesh.inp'))
writer.SetOverwrite(1)


def write_ours():
    writer.Modified()
    writer.Write()
    if writer.GetErrorCode():
        raise RuntimeError(writer.GetLastError())


figures['write'] = median_seconds(write_ours)
theirs = meshio.read(mesh_file, file_format='abaqus')
theirs.points = moved
figures['meshio_write'] = median_seconds(lambda: meshio.write(os.path.join(out, 'meshio.inp'), theirs, file_format='abaqus'))

# a further variant of the deck: the hole moved, deformed, the FEM verdict, the deck written
plate = meshfile.open_mesh(deck)
plate.Update()
start = time.perf_counter()   # the first variant's deformation: sampling (the deck's boundary faces), factorization, verdict
deform = vtkfoam.morph(plate, 'hole1', (0, 0, 0), fixed=['fixed', 'load'])
figures['first'] = time.perf_counter() - start
dvs = mlsdeform.DesignVariables(deform)
dvs.addHandleDV('x1', [deform.GetInputAlgorithm(1, 0)], translate=[1, 0, 0], lower=-0.5, upper=0.5)
values = iter(np.linspace(-0.3, 0.3, runs + 1))
dvs.setDesignVars({'x1': next(values)})
dvs._updated()  # the set-up (sampling, factorization) once, as a design of experiments pays it once
verdicts = []


def variant():
    dvs.setDesignVars({'x1': next(values)})
    dvs._updated()
    quality = mlsdeform.meshQuality(dvs)
    verdicts.append(mlsdeform.passes(quality))
    meshfile.save_variant(deform, os.path.join(out, 'deck-variant', os.path.basename(deck)), overwrite=True)


figures['variant'] = median_seconds(variant)
figures['variants_pass'] = all(verdicts)
print('DECKBENCHMARK ' + json.dumps(figures), flush=True)
