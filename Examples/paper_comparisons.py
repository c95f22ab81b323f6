"""Reproduces the paper's comparisons (sections 4 and 7.2-7.3) with the plugin's filters and writes
CSV files, PNG plots and a Markdown report (report.md) into OUTPUT_DIR.

    pvbatch paper_comparisons.py PLUGIN FANDISK.off OUTPUT_DIR [--quick]

Fig. 3:  the 33 x 33 plane (1089 vertices), fixed strip x <= 0.1, handle strip x >= 0.9 lifted by
         0.3; bending and stretching; Shell Deform as ground truth against MLS Deform with every
         basis (1000 shape functions on the plane, EnergyDiscretization SurfaceVertices, eq. 11):
         RMS and max deviation relative to the handle displacement, and mean-curvature images.
Fig. 4:  set-up time and peak memory of MLS Deform on fandisk against k for Biharmonic,
         Wendland (cover 50) and MLS (cover 5), each run in its own process (memory = its peak
         resident size minus that of a process that loads the same data without deforming).
Fig. 12: a tetrahedral box with a spherical hole (gmsh), outer boundary fixed, the sphere moved:
         min scaled Jacobian before and after for MLS and Triharmonic (Deformation Quality).
Fig. 13: a hexahedral pipe, one end fixed, the other moved sideways: min scaled Jacobian before
         and after.
         Each configuration is run --repeats times (default 3) and the median is reported; one whose
         first run takes over a minute is run once (its spread is small against its length).
--quick runs Fig. 4 for k = 1000 (MLS also 2000) only, once: what the test suite checks.
"""
import csv
import json
import os
import subprocess
import sys
import time

import numpy as np
from paraview import servermanager as sm
from paraview.simple import Curvature, Delete, LoadPlugin, OpenDataFile, Plane, Triangulate
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import fandisk_scene  # noqa: E402
from fandisk_scene import box_region  # noqa: E402

LIFT = 0.3
SPHERE_MOTION = 0.4  # of the 0.5 gap between the sphere and the box
FIG3_BASES = [  # (label, Basis, Cover)
    ('MLS s=5', 'MLS', 5), ('Wendland s=5', 'Wendland', 5), ('Wendland s=50', 'Wendland', 50),
    ('Gaussian s=5', 'Gaussian', 5), ('Gaussian s=50', 'Gaussian', 50),
    ('Biharmonic', 'Biharmonic', 5), ('Triharmonic', 'Triharmonic', 5)]
# (label, Basis, Cover, k of the full report, k of --quick): the paper's range, 1k to 10k.
FIG4_K = [1000, 2000, 4000, 6000, 8000, 10000]
FIG4_BASES = [('Biharmonic', 'Biharmonic', 5, FIG4_K, [1000]),
              ('Wendland s=50', 'Wendland', 50, FIG4_K, [1000]),
              ('MLS s=5', 'MLS', 5, FIG4_K, [1000, 2000])]
LONG_RUN_SECONDS = 60  # a configuration whose first run takes longer is not repeated


def plugin_proxies(plugin):
    """The plugin's proxies, here and in fandisk_scene (whose region helpers this script uses)."""
    LoadPlugin(plugin, remote=False, ns=globals())
    fandisk_scene.ConstraintRegion = globals()['ConstraintRegion']


def points_of(proxy):
    return vtk_to_numpy(sm.Fetch(proxy).GetPoints().GetData()).astype(float)


def field(proxy, name):
    return sm.Fetch(proxy).GetFieldData().GetArray(name).GetValue(0)


def write_csv(path, header, rows):
    with open(path, 'w', newline='') as f:
        writer = csv.writer(f)
        writer.writerow(header)
        writer.writerows(rows)


def markdown_table(header, rows):
    lines = ['| ' + ' | '.join(header) + ' |', '|' + ' --- |' * len(header)]
    for row in rows:
        lines.append('| ' + ' | '.join(('%.4g' % v) if isinstance(v, float) else str(v) for v in row) + ' |')
    return '\n'.join(lines)


# ---------------------------------------------------------------------------------------------
# Fig. 3: deviation from the shell ground truth, per basis, bending and stretching
def figure3(out_dir):
    plane = Triangulate(Input=Plane(Origin=[0, 0, 0], Point1=[1, 0, 0], Point2=[0, 1, 0], XResolution=32, YResolution=32))
    plane.UpdatePipeline()
    x = points_of(plane)
    margin = 0.01
    fixed = box_region(plane, 'Fixed', [-margin, -margin, -margin], [0.1 + 1e-6, 1 + margin, margin])
    handle = box_region(plane, 'Handle', [0.9 - 1e-6, -margin, -margin], [1 + margin, 1 + margin, margin],
                        Translation=[0, 0, LIFT])
    rows, curvature = [], {}
    for energy, stretch, bend in (('bending', 0, 1), ('stretching', 1, 0)):
        truth = ShellDeform(Input=plane, Regions=[fixed, handle], StretchWeight=stretch, BendWeight=bend)  # noqa: F821
        fandisk_scene.update_deformation(truth)
        reference = points_of(truth)
        curvature[(energy, 'Shell (ground truth)')] = mean_curvature(truth)
        for label, basis, cover in FIG3_BASES:
            deform = MLSDeform(Input=plane, Regions=[fixed, handle], StretchWeight=stretch, BendWeight=bend,  # noqa: F821
                               Basis=basis, Cover=cover, NumberOfSamples=1000, VolumeSampleFraction=0.0,
                               EnergyDiscretization='SurfaceVertices')
            fandisk_scene.update_deformation(deform)
            deviation = np.linalg.norm(points_of(deform) - reference, axis=1) / LIFT
            rms, largest = float(np.sqrt(np.mean(deviation ** 2))), float(deviation.max())
            rows.append([energy, label, rms, largest, field(deform, 'SetupTime')])
            curvature[(energy, label)] = mean_curvature(deform)
            print('Fig. 3 %s %-14s RMS %.4f max %.4f of the handle displacement' % (energy, label, rms, largest), flush=True)
            Delete(deform)
        Delete(truth)
    header = ['energy', 'basis', 'rms_deviation', 'max_deviation', 'setup_seconds']
    write_csv(os.path.join(out_dir, 'fig3_deviation.csv'), header, rows)
    plot_fig3(out_dir, rows, curvature, x)
    return header, rows


def mean_curvature(deformed):
    curvature = Curvature(Input=deformed, CurvatureType='Mean')
    data = sm.Fetch(curvature)
    values = vtk_to_numpy(data.GetPointData().GetArray('Mean_Curvature')).astype(float)
    Delete(curvature)
    return values


def plot_fig3(out_dir, rows, curvature, x):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri
    labels = [label for label, _, _ in FIG3_BASES]
    fig, ax = plt.subplots(figsize=(9, 4))
    width = 0.38
    for i, energy in enumerate(('bending', 'stretching')):
        values = [r[2] * 100 for r in rows if r[0] == energy]
        ax.bar(np.arange(len(labels)) + (i - 0.5) * width, values, width, label=energy)
    ax.axhline(2, color='k', linestyle='--', linewidth=1, label='2% target (MLS, bending)')
    ax.set_xticks(np.arange(len(labels)), labels, rotation=20)
    ax.set_yscale('log')
    ax.set_ylabel('RMS deviation from the shell\n(% of the handle displacement)')
    ax.set_title('Fig. 3: subspaces of 1000 shape functions against the shell (1089-vertex plane)')
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, 'fig3_deviation.png'), dpi=110)
    plt.close(fig)
    # mean curvature of the deformed plane seen from above, one row per energy
    triangulation = mtri.Triangulation(x[:, 0], x[:, 1])
    interior = (x[:, 0] > 0.05) & (x[:, 0] < 0.95) & (x[:, 1] > 0.05) & (x[:, 1] < 0.95)
    methods = ['Shell (ground truth)'] + labels
    fig, axes = plt.subplots(2, len(methods), figsize=(2.1 * len(methods), 4.6))
    for r, energy in enumerate(('bending', 'stretching')):
        limit = np.percentile(np.abs(curvature[(energy, methods[0])][interior]), 98) or 1.0
        for c, method in enumerate(methods):
            ax = axes[r, c]
            ax.tripcolor(triangulation, np.clip(curvature[(energy, method)], -limit, limit), shading='gouraud',
                         cmap='coolwarm', vmin=-limit, vmax=limit)
            ax.set_aspect('equal')
            ax.set_xticks([])
            ax.set_yticks([])
            if r == 0:
                ax.set_title(method, fontsize=8)
            if c == 0:
                ax.set_ylabel(energy)
    fig.suptitle('Fig. 3: mean curvature (same color range per row as the ground truth)', fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, 'fig3_mean_curvature.png'), dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------------------------------------
# Fig. 4: time and memory against k, each configuration in its own process
def memory_kib(entry):
    """VmRSS (resident) or VmHWM (peak resident) of this process, KiB."""
    with open('/proc/self/status') as f:
        return next(int(line.split()[1]) for line in f if line.startswith(entry + ':'))


def figure4_case(plugin, fandisk, basis, cover, k):
    """Child process: one deformation of fandisk; prints a JSON line with its timings."""
    plugin_proxies(plugin)
    part = OpenDataFile(fandisk)
    part.UpdatePipeline()
    result = {'basis': basis, 'cover': cover, 'k': k}
    if k > 0:  # (k = 0: only the data, for comparison)
        fixed, handle = fandisk_scene.fixed_and_handle(part, part.GetDataInformation().GetBounds())
        deform = MLSDeform(Input=part, Regions=[fixed, handle], Basis=basis, Cover=cover, NumberOfSamples=k)  # noqa: F821
        fixed.UpdatePipeline()
        handle.UpdatePipeline()
        with open('/proc/self/clear_refs', 'w') as f:
            f.write('5')  # resets the peak resident size (VmHWM), Linux >= 4.0
        before = memory_kib('VmRSS')
        start = time.perf_counter()
        fandisk_scene.update_deformation(deform)
        result['wall_seconds'] = time.perf_counter() - start
        result['memory_mib'] = (memory_kib('VmHWM') - before) / 1024.0
        result['setup_seconds'] = field(deform, 'SetupTime')
        result['solve_seconds'] = field(deform, 'SolveTime')
        result['handle_residual'] = field(deform, 'HandleResidual')
    print('RESULT ' + json.dumps(result), flush=True)


def run_case(plugin, fandisk, basis, cover, k):
    """One Fig. 4 configuration in a fresh pvbatch process (memory is not shared between runs)."""
    output = subprocess.run([os.environ.get('PVBATCH', 'pvbatch'), os.path.abspath(__file__), plugin, fandisk, '-',
                             '--fig4-case', basis, str(cover), str(k)], stdout=subprocess.PIPE, text=True).stdout
    lines = [line for line in output.splitlines() if line.startswith('RESULT ')]
    if not lines:
        raise RuntimeError('Fig. 4 case %s k=%d failed:\n%s' % (basis, k, output))
    return json.loads(lines[-1][len('RESULT '):])


def figure4(plugin, fandisk, out_dir, quick, repeats):
    rows = []
    for label, basis, cover, full_ks, quick_ks in FIG4_BASES:
        for k in (quick_ks if quick else full_ks):
            runs = [run_case(plugin, fandisk, basis, cover, k)]
            while len(runs) < repeats and runs[0]['setup_seconds'] < LONG_RUN_SECONDS:
                runs.append(run_case(plugin, fandisk, basis, cover, k))
            median = lambda key: float(np.median([r[key] for r in runs]))
            rows.append([label, k, median('setup_seconds'), median('solve_seconds'), median('memory_mib'), len(runs)])
            print('Fig. 4 %-14s k=%5d set-up %.2f s, solve %.4f s, memory %.0f MiB (median of %d)' % (label, k,
                  rows[-1][2], rows[-1][3], rows[-1][4], len(runs)), flush=True)
    header = ['basis', 'k', 'setup_seconds', 'solve_seconds', 'memory_mib', 'runs']
    write_csv(os.path.join(out_dir, 'fig4_performance.csv'), header, rows)
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for label in [b[0] for b in FIG4_BASES]:
        mine = [r for r in rows if r[0] == label]
        left.plot([r[1] for r in mine], [1000 * r[2] for r in mine], 'o-', label=label)
        right.plot([r[1] for r in mine], [r[4] for r in mine], 'o-', label=label)
    left.set_ylabel('set-up time (ms)')
    right.set_ylabel('peak memory of the deformation (MiB)')
    for ax in (left, right):
        ax.set_xlabel('number of shape functions k')
        ax.set_yscale('log')
        ax.legend()
    fig.suptitle('Fig. 4: MLS Deform on fandisk (6475 vertices), volumetric energies')
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, 'fig4_performance.png'), dpi=110)
    plt.close(fig)
    return header, rows


# ---------------------------------------------------------------------------------------------
# Fig. 12 and 13: volume meshes, min scaled Jacobian before and after
def quality(deformed, original):
    measure = DeformationQuality(Input=deformed, Original=original)  # noqa: F821
    table = sm.Fetch(measure, idx=2)
    value = lambda row, column: table.GetValueByName(row, column).ToDouble()
    result = {'min_sj_before': value(0, 'OriginalMin'), 'min_sj_after': value(0, 'Min'),
              'inverted_after': int(value(3, 'Max')), 'max_nonorth_before': value(1, 'OriginalMax'),
              'max_nonorth_after': value(1, 'Max')}
    Delete(measure)
    return result


def sphere_hole_mesh(out_dir):
    """gmsh: the box [0,2]^3 minus a ball of radius 0.5 at its center, tetrahedra only."""
    geo = os.path.join(out_dir, 'box_with_hole.geo')
    with open(geo, 'w') as f:
        f.write('SetFactory("OpenCASCADE");\nBox(1) = {0, 0, 0, 2, 2, 2};\nSphere(2) = {1, 1, 1, 0.5};\n'
                'BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };\n'
                'Physical Volume(1) = {3};\nMesh.MeshSizeMax = 0.16;\nMesh.MeshSizeMin = 0.08;\n'
                'Mesh.Optimize = 1;\n')
    mesh = os.path.join(out_dir, 'box_with_hole.vtk')
    subprocess.run(['gmsh', '-3', '-format', 'vtk', '-o', mesh, geo], check=True, stdout=subprocess.DEVNULL)
    return mesh


def figure12(out_dir):
    from paraview.simple import LegacyVTKReader
    box = LegacyVTKReader(FileNames=[sphere_hole_mesh(out_dir)])
    box.UpdatePipeline()
    cells = box.GetDataInformation().GetNumberOfCells()
    fixed = box_region(box, 'Fixed', [0.001] * 3, [1.999] * 3, InsideOut=1)
    handle = ConstraintRegion(Input=box, Role='Handle', Translation=[SPHERE_MOTION, 0, 0])  # noqa: F821
    handle.Region = 'Sphere'
    handle.Region.Center = [1, 1, 1]
    handle.Region.Radius = 0.52
    rows = []
    for label, basis in (('MLS s=5', 'MLS'), ('Triharmonic', 'Triharmonic')):
        deform = MLSDeform(Input=box, Regions=[fixed, handle], Basis=basis, NumberOfSamples=1000)  # noqa: F821
        fandisk_scene.update_deformation(deform)
        q = quality(deform, box)
        rows.append([label, cells, q['min_sj_before'], q['min_sj_after'], q['inverted_after'], q['max_nonorth_after'],
                     field(deform, 'HandleResidual')])
        print('Fig. 12 %-12s %d tetrahedra: min scaled Jacobian %.3f -> %.3f, inverted %d' % (label, cells,
              q['min_sj_before'], q['min_sj_after'], q['inverted_after']), flush=True)
        Delete(deform)
    header = ['method', 'cells', 'min_scaled_jacobian_before', 'min_scaled_jacobian_after', 'inverted_after',
              'max_non_orthogonality_after', 'handle_residual']
    write_csv(os.path.join(out_dir, 'fig12_sphere_hole.csv'), header, rows)
    return header, rows


def hexahedral_pipe(inner=0.5, outer=1.0, length=6.0, nr=3, nt=24, nz=36):
    """A source of a pipe of nr x nt x nz hexahedra around the z axis."""
    from paraview.simple import PVTrivialProducer
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import VTK_HEXAHEDRON, vtkUnstructuredGrid
    r = np.linspace(inner, outer, nr + 1)
    t = np.linspace(0, 2 * np.pi, nt, endpoint=False)
    z = np.linspace(0, length, nz + 1)
    R, T, Z = np.meshgrid(r, t, z, indexing='ij')
    xyz = np.column_stack([(R * np.cos(T)).ravel(), (R * np.sin(T)).ravel(), Z.ravel()])
    points = vtkPoints()
    points.SetData(numpy_to_vtk(xyz, deep=True))
    grid = vtkUnstructuredGrid()
    grid.SetPoints(points)
    index = lambda i, j, k: (i * nt + j % nt) * (nz + 1) + k
    for i in range(nr):
        for j in range(nt):
            for k in range(nz):
                grid.InsertNextCell(VTK_HEXAHEDRON, 8, [index(i, j, k), index(i + 1, j, k), index(i + 1, j + 1, k),
                                                        index(i, j + 1, k), index(i, j, k + 1), index(i + 1, j, k + 1),
                                                        index(i + 1, j + 1, k + 1), index(i, j + 1, k + 1)])
    source = PVTrivialProducer()
    source.GetClientSideObject().SetOutput(grid)
    return source


def figure13(out_dir):
    pipe = hexahedral_pipe()
    pipe.UpdatePipeline()
    cells = pipe.GetDataInformation().GetNumberOfCells()
    fixed = box_region(pipe, 'Fixed', [-1.1, -1.1, -0.01], [1.1, 1.1, 0.01])
    handle = box_region(pipe, 'Handle', [-1.1, -1.1, 5.99], [1.1, 1.1, 6.01], Translation=[1.5, 0, 0])
    deform = MLSDeform(Input=pipe, Regions=[fixed, handle], NumberOfSamples=1000)  # noqa: F821
    fandisk_scene.update_deformation(deform)
    q = quality(deform, pipe)
    rows = [['MLS s=5', cells, q['min_sj_before'], q['min_sj_after'], q['inverted_after'], q['max_nonorth_after'],
             field(deform, 'HandleResidual')]]
    print('Fig. 13 %d hexahedra: min scaled Jacobian %.3f -> %.3f, inverted %d' % (cells, q['min_sj_before'],
          q['min_sj_after'], q['inverted_after']), flush=True)
    header = ['method', 'cells', 'min_scaled_jacobian_before', 'min_scaled_jacobian_after', 'inverted_after',
              'max_non_orthogonality_after', 'handle_residual']
    write_csv(os.path.join(out_dir, 'fig13_hex_pipe.csv'), header, rows)
    return header, rows


def main():
    plugin, fandisk, out_dir = sys.argv[1:4]
    if '--fig4-case' in sys.argv:
        basis, cover, k = sys.argv[sys.argv.index('--fig4-case') + 1:][:3]
        figure4_case(plugin, fandisk, basis, float(cover), int(k))
        return
    quick = '--quick' in sys.argv
    repeats = 1 if quick else int(sys.argv[sys.argv.index('--repeats') + 1]) if '--repeats' in sys.argv else 3
    os.makedirs(out_dir, exist_ok=True)
    plugin_proxies(plugin)
    sections = [
        ('Fig. 3: deviation from the shell ground truth (relative to the handle displacement 0.3)',
         figure3(out_dir), ['fig3_deviation.png', 'fig3_mean_curvature.png']),
        ('Fig. 4: set-up time and memory against k (fandisk, volumetric energies)',
         figure4(plugin, fandisk, out_dir, quick, repeats), ['fig4_performance.png']),
        ('Fig. 12: tetrahedral box with a spherical hole (radius 0.5 in [0, 2]^3), sphere moved by %g' % SPHERE_MOTION, figure12(out_dir), []),
        ('Fig. 13: hexahedral pipe, one end moved sideways by 1.5', figure13(out_dir), []),
    ]
    with open(os.path.join(out_dir, 'report.md'), 'w') as f:
        f.write('# Paper comparisons (Sieger, Menzel, Botsch)\n\nGenerated by `Examples/run-comparisons.sh`%s '
                'on %s. CSV files with the same numbers are next to this report.\n\n'
                % (' (quick)' if quick else '', time.strftime('%Y-%m-%d')))
        for title, (header, rows), images in sections:
            f.write('## %s\n\n%s\n\n' % (title, markdown_table(header, rows)))
            for image in images:
                f.write('![%s](%s)\n\n' % (image, image))
    print('report written to %s' % os.path.join(out_dir, 'report.md'))


if __name__ == '__main__':
    main()
