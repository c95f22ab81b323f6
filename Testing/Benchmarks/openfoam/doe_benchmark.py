"""MLS Deform's side of the design-of-experiments benchmark (run-doe-benchmark.sh): on the hull
case, three design variables on the hull (dx: translation along x in m, yaw: rotation about z in
degrees, sx: the hull's length scale), a Latin hypercube of SAMPLES points (seed 0), run as the
command line mlsdeform-doe.py runs it (glibc's allocator settings of mlsdeform/allocator.py,
mlsdeform.cli.setUp of a design file: a plain VTK pipeline
in Debian's python3; then mlsdeform.designOfExperiments: deform, quality verdict, write a linked
variant), timed from the process's start; then, for the first MOVEMESH variants, the hull patch's
prescribed displacement (the same map as the handle's, in the patch's point order) into a
0/pointDisplacement for moveMesh. Prints one JSON line (DOEBENCH {...}).
Usage: python3 doe_benchmark.py PLUGIN_FOLDER CASE.foam OUT SAMPLES MOVEMESH"""
import json
import math
import os
import re
import runpy
import sys
import time

# the process's start, before the restart with the batch allocator that mlsdeform-doe.py makes too
start = float(os.environ.setdefault('MLSDEFORM_BENCHMARK_START', repr(time.time())))
plugin_folder, foam, out, samples, movemesh = sys.argv[1:6]
samples, movemesh = int(samples), int(movemesh)
runpy.run_path(os.path.join(plugin_folder, 'mlsdeform', 'allocator.py'))['restartWithBatchAllocator']()
sys.path.insert(0, plugin_folder)
import numpy as np  # noqa: E402
import mlsdeform  # noqa: E402
from mlsdeform import cli, vtkfoam  # noqa: E402

VARIABLES = [('dx', 'translate', [1, 0, 0], -0.2, 0.2), ('yaw', 'rotate', [0, 0, 1], -3, 3), ('sx', 'scale', [1, 0, 0], -0.05, 0.05)]
design_file = os.path.join(out, 'design.json')
os.makedirs(out, exist_ok=True)
with open(design_file, 'w') as f:
    json.dump({'case': os.path.abspath(foam), 'handle': ['hull'], 'fixed': ['inlet', 'outlet'],
               'slip': ['sideYmin', 'sideYmax', 'bottom', 'top'],
               'variables': [{'name': name, kind: axis, 'lower': lower, 'upper': upper} for name, kind, axis, lower, upper in VARIABLES]}, f)


def peak_mib():
    for line in open('/proc/self/status'):
        if line.startswith('VmHWM:'):
            return int(line.split()[1]) / 1024.0


result = {'startup_s': time.time() - start, 'samples': samples}
began = time.time()
dvs = cli.setUp(design_file)
deformed = dvs.deformer
result['setup_s'] = time.time() - began   # read, sample, Phi, factorization, the undeformed solve
result['peak_mib_setup'] = peak_mib()
began = time.time()
report = mlsdeform.designOfExperiments(dvs, os.path.join(out, 'variants'), samples=samples, seed=0)
result['batch_s'] = time.time() - began
result['process_s'] = time.time() - start
result['peak_mib'] = peak_mib()
seconds = [r['seconds'] for r in report]
result['variant_s'] = {'first': seconds[0], 'median': float(np.median(seconds)), 'mean': float(np.mean(seconds)),
                       'max': float(np.max(seconds))}
result['ok'] = sum(r['ok'] for r in report)
result['quality'] = {key: float(max(r[key] for r in report)) for key in mlsdeform.experiments.QUALITY}


def own_bytes(folder):
    """Bytes of the files a variant holds itself (links excluded)."""
    total = 0
    for path, _, files in os.walk(folder):
        for f in files:
            st = os.lstat(os.path.join(path, f))
            if not os.path.islink(os.path.join(path, f)):
                total += st.st_size
    return total


# where a further variant's time goes: five more variants, each timed in parts (the update with and
# without the mesh-quality pass, the write of a linked variant); medians
parts = {'deform_s': [], 'quality_s': [], 'write_s': [], 'solve_s': []}
for i, values in enumerate([[r[name] for name, *_ in VARIABLES] for r in report[:5]]):
    dvs.setDesignVars({name: -v for (name, *_), v in zip(VARIABLES, values)})
    deformed.SetMeshQuality(0)
    t = time.time()
    dvs.update()
    parts['deform_s'].append(time.time() - t)
    parts['solve_s'].append(dvs._algorithm.GetOutputDataObject(0).GetFieldData().GetArray('SolveTime').GetTuple1(0))
    deformed.SetMeshQuality(1)
    t = time.time()
    dvs.update()   # the same update again with the quality pass: its extra time is the pass
    parts['quality_s'].append(time.time() - t - parts['deform_s'][-1])
    t = time.time()
    vtkfoam.save_variant(deformed, os.path.join(out, 'parts-%d' % i, 'case.foam'), link=True)
    parts['write_s'].append(time.time() - t)
result['parts_s'] = {key: float(np.median(v)) for key, v in parts.items()}

written = [r for r in report if r['path']]
disk = [own_bytes(os.path.dirname(r['path'])) for r in written]
points = [os.path.getsize(os.path.join(os.path.dirname(r['path']), 'constant', 'polyMesh', 'points')) for r in written]
result['disk_per_variant_bytes'] = float(np.median(disk)) if disk else 0
result['points_file_bytes'] = float(np.median(points)) if points else 0
result['values'] = [[r[name] for name, *_ in VARIABLES] for r in report]


# -- the same variants for moveMesh: the hull's prescribed displacement in its patch point order ----
def foam_list(path, kind):
    """The lists of a binary polyMesh file (as snappyHexMesh writes the hull case): faces, a
    faceCompactList (offsets, labels; 32-bit labels), or points (n x 3 doubles)."""
    with open(path, 'rb') as f:
        data = f.read()
    header_end = data.index(b'}', data.index(b'FoamFile')) + 1
    if b'binary' not in data[:header_end]:
        raise RuntimeError('%s is not binary: the benchmark reads the binary hull case' % path)
    dtype, per = (np.float64, 3) if kind == 'points' else (np.int32, 1)
    lists, position = [], header_end
    for _ in range(2 if kind == 'faces' else 1):
        match = re.compile(rb'\s*(\d+)\s*\(').search(data, position)
        values = np.frombuffer(data, dtype=dtype, count=int(match.group(1)) * per, offset=match.end())
        lists.append(values)
        position = match.end() + values.nbytes + 1
    return lists


def hull_points(case):
    """The hull patch's points in OpenFOAM's order (each point at its first appearance in the
    patch's faces) and their positions."""
    boundary = open(os.path.join(case, 'constant', 'polyMesh', 'boundary')).read()
    block = boundary[boundary.index('hull'):]
    n_faces = int(re.search(r'nFaces\s+(\d+)', block).group(1))
    start_face = int(re.search(r'startFace\s+(\d+)', block).group(1))
    offsets, labels = foam_list(os.path.join(case, 'constant', 'polyMesh', 'faces'), 'faces')
    ids = labels[offsets[start_face]:offsets[start_face + n_faces]]
    _, first = np.unique(ids, return_index=True)
    order = ids[np.sort(first)]
    points = foam_list(os.path.join(case, 'constant', 'polyMesh', 'points'), 'points')[0].reshape(-1, 3)
    return points[order]


if movemesh > 0:
    case = os.path.dirname(os.path.abspath(foam))
    x = hull_points(case)
    pivot = np.array(deformed.GetInputAlgorithm(1, 0).GetPivot())
    template = open(os.path.join(case, '0', 'pointDisplacement')).read()
    for i, values in enumerate(result['values'][:movemesh]):
        dx, yaw, sx = values
        c, s = math.cos(math.radians(yaw)), math.sin(math.radians(yaw))
        R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        A = R @ (np.eye(3) + np.diag([sx, 0, 0]))                 # DesignVariables.h: R_dv (I + S_dv)
        d = np.array([dx, 0, 0]) + (x - pivot) @ A.T - (x - pivot)
        rows = '\n'.join('(%.17g %.17g %.17g)' % tuple(v) for v in d)
        text = re.sub(r'hull\s*\{[^}]*\}', 'hull { type fixedValue; value nonuniform List<vector> %d\n(\n%s\n); }' % (len(d), rows),
                      template, count=1)
        with open(os.path.join(out, 'pointDisplacement-%d' % i), 'w') as f:
            f.write(text)
print('DOEBENCH ' + json.dumps(result), flush=True)
