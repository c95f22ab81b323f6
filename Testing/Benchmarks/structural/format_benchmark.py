"""The formats benchmark's runs (run-format-benchmark.sh): for each solver format, a mesh of about
N nodes made by a third-party writer (Gmsh: .inp, .msh, .su2, .bdf; ParaView: .exo, .cgns; OpenFOAM's
foamMeshToFluent: Fluent .msh), then the median of RUNS runs of copying the file (shutil.copyfile:
the floor) and of writing a variant with every node moved (the variant writer's own work: the
file's layout read once, as a design of experiments reads it). Prints one JSON line per format
(FORMATBENCHMARK {...}).

    pvpython format_benchmark.py PLUGIN WORK NODES RUNS
"""
import json
import os
import shutil
import statistics
import subprocess
import sys
import time

import numpy as np
from paraview import servermanager as sm
from paraview.simple import ExodusIIWriter, LoadPlugin, SaveData, Tetrahedralize, Wavelet
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints

plugin, work, nodes, runs = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
LoadPlugin(plugin, remote=False, ns=globals())
import mlsdeform  # noqa: E402 (the plugin's classes through their Python wrapping, once it is loaded)
os.makedirs(work, exist_ok=True)


def median(run):
    times = []
    for _ in range(runs):
        began = time.perf_counter()
        run()
        times.append(time.perf_counter() - began)
    return statistics.median(times)


def gmsh_box(path, fmt):
    """A box meshed by Gmsh into tetrahedra of about `nodes` nodes."""
    geo = os.path.join(work, 'box.geo')
    with open(geo, 'w') as f:
        size = (4.23 / nodes) ** (1 / 3)  # Gmsh's linear tetrahedra of size h in this 4-unit box: about 4.23 / h^3 nodes
        f.write('SetFactory("OpenCASCADE");\nBox(1) = {0, 0, 0, 2, 2, 1};\nPhysical Volume("box") = {1};\n'
                'Physical Surface("skin") = Surface{:};\nMesh.CharacteristicLengthMax = %g;\n' % size)
    subprocess.run(['gmsh', '-3', geo, '-format', fmt, '-o', path], check=True, stdout=subprocess.DEVNULL)


def wavelet(path, writer):
    """ParaView's Wavelet as tetrahedra, written by one of ParaView's writers."""
    n = round(nodes ** (1 / 3)) - 1
    box = Tetrahedralize(Input=Wavelet(WholeExtent=[0, n, 0, n, 0, n]))
    writer(path, box)


def fluent(path):
    """blockMesh's box of about `nodes` points, written by foamMeshToFluent."""
    case = os.path.join(work, 'fluent-case')
    n = round(nodes ** (1 / 3)) - 1
    os.makedirs(os.path.join(case, 'system'), exist_ok=True)
    header = 'FoamFile { version 2.0; format ascii; class dictionary; object %s; }\n'
    files = {'controlDict': 'application icoFoam; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1; '
                            'writeControl timeStep; writeInterval 1;\n',
             'blockMeshDict': 'convertToMeters 1; vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1));\n'
                              'blocks (hex (0 1 2 3 4 5 6 7) (%d %d %d) simpleGrading (1 1 1));\n'
                              'boundary (walls { type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2) (0 3 2 1) (4 5 6 7)); });\n'
                              % (n, n, n),
             'fvSchemes': 'ddtSchemes { default Euler; } gradSchemes { default Gauss linear; } divSchemes { default none; } '
                          'laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; } '
                          'snGradSchemes { default corrected; }\n',
             'fvSolution': 'solvers { }\n'}
    for name, text in files.items():
        with open(os.path.join(case, 'system', name), 'w') as f:
            f.write(header % name + text)
    subprocess.run(['bash', '-c', 'source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1; cd "%s" && blockMesh > log.blockMesh '
                    '&& foamMeshToFluent > log.foamMeshToFluent' % case], check=True)
    shutil.copyfile(os.path.join(case, 'fluentInterface', 'fluent-case.msh'), path)


makers = {
    'Abaqus deck (.inp)': ('box.inp', lambda p: gmsh_box(p, 'inp')),
    'Gmsh (.msh 4.1 ASCII)': ('box.msh', lambda p: gmsh_box(p, 'msh41')),
    'SU2 (.su2)': ('box.su2', lambda p: gmsh_box(p, 'su2')),
    'Nastran (.bdf, small field)': ('box.bdf', lambda p: gmsh_box(p, 'bdf')),
    'Exodus II (.exo, ParaView)': ('box.exo', lambda p: wavelet(p, lambda q, s: ExodusIIWriter(FileName=q, Input=s).UpdatePipeline())),
    'CGNS (.cgns, ParaView)': ('box.cgns', lambda p: wavelet(p, lambda q, s: SaveData(q, proxy=s))),
    'Fluent (.msh, foamMeshToFluent)': ('fluent.msh', fluent),
}
for name, (file, make) in makers.items():
    source = os.path.join(work, 'source', file)
    os.makedirs(os.path.dirname(source), exist_ok=True)
    if not os.path.exists(source):
        make(source)
    reader = MeshFileReader(FileName=source)  # noqa: F821 (the plugin's)
    grid = sm.Fetch(reader)
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    moved = grid.NewInstance()
    moved.ShallowCopy(grid)
    shifted = vtkPoints()
    shifted.SetData(numpy_to_vtk(points + 1e-3 * np.sin(points[:, [1, 2, 0]]), deep=True))
    moved.SetPoints(shifted)
    variant_writer = mlsdeform.deformer._load_wrapping(readers=True).vtkMeshVariantWriter()
    variant_writer.SetInputData(moved)
    target = os.path.join(work, 'variant', file)
    variant_writer.SetFileName(target)
    variant_writer.SetOverwrite(1)

    def write():
        variant_writer.Modified()
        variant_writer.Write()
        if variant_writer.GetErrorCode():
            raise RuntimeError(variant_writer.GetLastError())
    write()  # the layout read once
    figures = {'format': name, 'nodes': grid.GetNumberOfPoints(), 'bytes': os.path.getsize(source),
               'copy': median(lambda: shutil.copyfile(source, os.path.join(work, 'copy-' + file))), 'variant': median(write)}
    print('FORMATBENCHMARK ' + json.dumps(figures), flush=True)
