"""MLS Deform's side of the OpenFOAM benchmark (run-openfoam-benchmark.sh): reads CASE.foam with
ParaView's OpenFOAM reader, moves the hull patch by the first translation with the inlet and
outlet fixed and the sides, bottom and top slipping (as moveMesh's 0/pointDisplacement does), writes
the variant case OUT/variant-0, then for each further translation changes only the handle's
motion on the same pipeline (a new variation: solve + write) into OUT/variant-1, 2, ...
Prints one JSON line with the phases' wall times, the peak RSS after each phase (VmHWM) and what
MLS Deform reports. --set NAME=VALUE (repeatable) sets an MLS Deform property (e.g. MeshQuality=0).
Usage: pvpython mls_benchmark.py PLUGIN EXAMPLES_OPENFOAM_DIR CASE.foam OUT [--set NAME=VALUE ...]
       DX,DY,DZ [DX,DY,DZ ...]"""
import json
import os
import sys
import time

start = time.time()
from paraview.simple import LoadPlugin  # noqa: E402

plugin, examples, case, out = sys.argv[1:5]
settings, motions = {}, []
arguments = iter(sys.argv[5:])
for argument in arguments:
    if argument == '--set':
        name, value = next(arguments).split('=', 1)
        settings[name] = float(value) if '.' in value or 'e' in value else int(value)
    else:
        motions.append([float(v) for v in argument.split(',')])
handle, fixed, slip = ['hull'], ['inlet', 'outlet'], ['sideYmin', 'sideYmax', 'bottom', 'top']

LoadPlugin(plugin, remote=False)
sys.path.insert(0, examples)
import openfoam_variant  # noqa: E402

os.makedirs(out, exist_ok=True)


def peak_mib():
    """The process' peak resident set size so far (VmHWM) in MiB."""
    for line in open('/proc/self/status'):
        if line.startswith('VmHWM:'):
            return int(line.split()[1]) / 1024.0


result = {'startup_s': time.time() - start, 'settings': settings, 'peak_mib': {'startup': peak_mib()}}


def field(proxy, name):
    array = proxy.GetDataInformation().GetFieldDataInformation().GetArrayInformation(name)
    return None if array is None else array.GetComponentRange(0)[0]


def report(deformed):
    return {name: field(deformed, name) for name in (
        'SetupTime', 'SolveTime', 'HandleResidual', 'FixedResidual', 'NumberOfSamples',
        'InvertedCells', 'OriginalInvertedCells', 'MaxNonOrthogonality', 'OriginalMaxNonOrthogonality',
        'MaxSkewness', 'OriginalMaxSkewness')}


t = time.time()
# Decompose polyhedra off: OpenFOAM's own cells, so that MLS Deform reports their quality (and no
# cell-centre points are added to deform)
reader = openfoam_variant.open_case(case, handle + fixed + slip, decompose_polyhedra=False)
result['read_s'] = time.time() - t
result['peak_mib']['read'] = peak_mib()
info = reader.GetDataInformation()
result['vtk_points'] = info.GetNumberOfPoints()
result['vtk_cells'] = info.GetNumberOfCells()

t = time.time()
deformed = openfoam_variant.morph(reader, handle, motions[0], fixed, slip, **settings)
result['deform_s'] = time.time() - t
result['peak_mib']['deform'] = peak_mib()
t = time.time()
openfoam_variant.save_variant(deformed, os.path.join(out, 'variant-0', 'case.foam'), overwrite=True)
result['write_s'] = time.time() - t
result['peak_mib']['write'] = peak_mib()
result['first_variant_s'] = time.time() - start
result['first'] = dict(report(deformed), translation=motions[0])

hull = deformed.Regions[0]  # morph() lists the handle regions first
result['further'] = []
for i, motion in enumerate(motions[1:], 1):
    t = time.time()
    hull.Translation = motion
    deformed.UpdatePipeline()
    if field(deformed, 'HandleResidual') is None:
        raise RuntimeError('MLS Deform failed on variant %d' % i)
    solved = time.time() - t
    openfoam_variant.save_variant(deformed, os.path.join(out, 'variant-%d' % i, 'case.foam'), overwrite=True)
    result['further'].append(dict(report(deformed), translation=motion, solve_s=solved,
                                  solve_write_s=time.time() - t))
result['peak_mib']['further'] = peak_mib()
result['total_s'] = time.time() - start
print('MLSBENCH ' + json.dumps(result))
