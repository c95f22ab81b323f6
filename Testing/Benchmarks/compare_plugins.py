"""Runs one scene with one build of the plugin and saves every output of the plugin's filters, or
compares two such runs bitwise (issue 28 point 7: a refactoring changes no result). Driven by
compare-plugins.sh, which describes the scenes and runs each build in its own processes:

    pvpython --no-mpi compare_plugins.py run SCENE PLUGIN DATA_DIR CASE.foam WORK_DIR
        (writes WORK_DIR/SCENE.pickle: {output/section/array: numpy array})
    pvpython --no-mpi compare_plugins.py compare A_DIR B_DIR
        (compares every *.pickle of the two folders; exit status 1 on any difference)

The scenes are the example scripts themselves (run with runpy, their pictures skipped), so that
they are checked as users run them; their proxies are then read from the scripts' globals."""
import os
import pickle
import runpy
import sys

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in Examples/
EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'Examples')
# Field data holding wall-clock times: they differ from run to run, so they are not compared.
TIMES = {'SetupTime', 'SolveTime'}


# ---------------------------------------------------------------------------------------------
# Saving outputs

def array_values(array):
    """A VTK array as a numpy array (strings as a numpy array of str)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    if array.IsNumeric():
        return vtk_to_numpy(array).copy()
    return np.array([array.GetVariantValue(i).ToString() for i in range(array.GetNumberOfValues())], dtype=str)


def save_arrays(arrays, key, values, skip=()):
    """Every array of a vtkFieldData (point, cell, field or row data) under key/name."""
    for i in range(values.GetNumberOfArrays()):
        array = values.GetAbstractArray(i)
        if array.GetName() not in skip:
            arrays['%s/%s' % (key, array.GetName())] = array_values(array)


def save_cells(arrays, key, cells):
    """A vtkCellArray as its connectivity and offsets (nothing if it is empty)."""
    if cells.GetNumberOfCells() == 0:
        return
    arrays[key + '.connectivity'] = array_values(cells.GetConnectivityArray())
    arrays[key + '.offsets'] = array_values(cells.GetOffsetsArray())


def save_data(arrays, key, data):
    """Points, cells and arrays of a data object; composite data block by block."""
    from vtkmodules.vtkCommonDataModel import (vtkCompositeDataSet, vtkPointSet, vtkPolyData, vtkTable,
                                               vtkUnstructuredGrid)
    save_arrays(arrays, key + '/field', data.GetFieldData(), skip=TIMES)
    if isinstance(data, vtkCompositeDataSet):
        blocks = data.NewIterator()
        blocks.InitTraversal()
        while not blocks.IsDoneWithTraversal():
            name = blocks.GetCurrentMetaData().Get(vtkCompositeDataSet.NAME()) or ''
            save_data(arrays, '%s/block%d:%s' % (key, blocks.GetCurrentFlatIndex(), name), blocks.GetCurrentDataObject())
            blocks.GoToNextItem()
        return
    if isinstance(data, vtkTable):
        save_arrays(arrays, key + '/row', data.GetRowData())
        return
    if isinstance(data, vtkPointSet) and data.GetPoints() is not None:
        arrays[key + '/points'] = array_values(data.GetPoints().GetData())
    if isinstance(data, vtkPolyData):
        for kind in ('Verts', 'Lines', 'Polys', 'Strips'):
            save_cells(arrays, '%s/cells/%s' % (key, kind.lower()), getattr(data, 'Get' + kind)())
    elif isinstance(data, vtkUnstructuredGrid):
        save_cells(arrays, key + '/cells/cells', data.GetCells())
        arrays[key + '/cells/types'] = array_values(data.GetCellTypesArray())
        if data.GetFaces() is not None:
            arrays[key + '/cells/faces'] = array_values(data.GetFaces())
    save_arrays(arrays, key + '/point', data.GetPointData())
    save_arrays(arrays, key + '/cell', data.GetCellData())


def save_output(arrays, name, proxy, port=0):
    """The current output of a proxy's port (the filter's own, not a fetched copy: pvpython
    --no-mpi runs the pipeline in this process)."""
    proxy.UpdatePipeline()
    save_data(arrays, '%s:%d' % (name, port), proxy.GetClientSideObject().GetOutputDataObject(port))


def run_example(script, *arguments):
    """Runs an example script as from the command line and returns its globals."""
    sys.argv = [script] + list(arguments)
    return runpy.run_path(script, run_name='__main__')


# ---------------------------------------------------------------------------------------------
# Scenes: each runs the examples' pipelines and saves the plugin's outputs into arrays.

def fandisk_scene():
    """The example scripts' fandisk helpers, with the pictures skipped (nothing is rendered)."""
    sys.path.insert(0, EXAMPLES)
    import fandisk_scene as scene
    scene.save_side_by_side = lambda *arguments, **options: None
    return scene


def scene_fandisk(arrays, plugin, data, case, work):
    """deform_fandisk.py, then a new handle motion and a new handle weight on its pipeline (the
    cached set-up re-solved, then refactorized)."""
    fandisk_scene()
    example = run_example(os.path.join(EXAMPLES, 'deform_fandisk.py'), plugin, os.path.join(data, 'fandisk.off'), work)
    deformed, handle = example['deformed'], example['handle']
    for name in ('fixed', 'handle', 'deformed'):
        save_output(arrays, name, example[name])
    height = example['height']
    handle.Translation = [0.05 * height, 0.1 * height, 0.02 * height]
    save_output(arrays, 'deformed-new-handle-motion', deformed)
    handle.Weight = 4.0
    save_output(arrays, 'deformed-new-handle-weight', deformed)


def scene_fandisk_constrained(arrays, plugin, data, case, work):
    """deform_fandisk_constrained.py: unconstrained and with feature lines and a planar face."""
    fandisk_scene()
    example = run_example(os.path.join(EXAMPLES, 'deform_fandisk_constrained.py'), plugin, os.path.join(data, 'fandisk.off'), work)
    for name in ('fixed', 'handle', 'planar', 'free', 'kept'):
        save_output(arrays, name, example[name])
    for index, region in enumerate(example['features']):
        save_output(arrays, 'feature%d' % index, region)


def scene_joint_primitives(arrays, plugin, data, case, work):
    """deform_joint_primitives.py: Primitive Detector on the joint and the deformations keeping
    its primitives."""
    fandisk_scene()
    example = run_example(os.path.join(EXAMPLES, 'deform_joint_primitives.py'), plugin, os.path.join(data, 'joint.off'), work)
    save_output(arrays, 'detector', example['detector'], 0)
    save_output(arrays, 'detector', example['detector'], 1)
    for name in ('fixed', 'handle', 'free', 'constrained'):
        save_output(arrays, name, example[name])
    for index, region in enumerate(example['kept']):
        save_output(arrays, 'kept%d' % index, region)


def scene_fandisk_filters(arrays, plugin, data, case, work):
    """Primitive Detector and MLS Sampler (both outputs) on fandisk at their defaults, and MLS
    Deform on the sampler's samples (the examples' regions)."""
    scene = fandisk_scene()
    scene.load_plugin(plugin)
    from paraview.simple import OpenDataFile, OutputPort
    part = OpenDataFile(os.path.join(data, 'fandisk.off'))
    part.UpdatePipeline()
    detector = scene.PrimitiveDetector(Input=part)
    save_output(arrays, 'detector', detector, 0)
    save_output(arrays, 'detector', detector, 1)
    sampler = scene.MLSSampler(Input=part)
    save_output(arrays, 'sampler', sampler, 0)
    save_output(arrays, 'sampler', sampler, 1)
    fixed, handle = scene.fixed_and_handle(part, part.GetDataInformation().GetBounds())
    deformed = scene.MLSDeform(Input=part, Regions=[fixed, handle], Samples=OutputPort(sampler, 0),
                               IntegrationPoints=OutputPort(sampler, 1))
    save_output(arrays, 'deformed-from-sampler', deformed)


def scene_openfoam(arrays, plugin, data, case, work):
    """Examples/OpenFOAM/morph_case.py on the sphereChannel case (its defaults: the sphere moved,
    inlet and outlet fixed, the sides slipping) with the variant case it writes, and Deformation
    Quality of the internal mesh against the original."""
    import paraview.simple as pvs
    variant = os.path.join(work, 'variant')
    example = run_example(os.path.join(EXAMPLES, 'OpenFOAM', 'morph_case.py'), plugin, case, variant)
    reader, deformed = example['reader'], example['deformed']
    save_output(arrays, 'deformed', deformed)
    for folder, _, files in os.walk(variant):
        for name in sorted(files):
            path = os.path.join(folder, name)
            with open(path, 'rb') as f:
                arrays['variant-file/' + os.path.relpath(path, variant)] = np.frombuffer(f.read(), dtype=np.uint8)

    def internal_mesh(source):
        merged = pvs.MergeBlocks(Input=pvs.ExtractBlock(Input=source, Selectors=['/Root/internalMesh']))
        if 'MergePoints' in merged.ListProperties():
            merged.MergePoints = 0  # the mesh's own points, in its order
        return merged
    quality = pvs.DeformationQuality(Input=internal_mesh(deformed), Original=internal_mesh(reader))
    for port in range(3):
        save_output(arrays, 'quality', quality, port)


SCENES = {'fandisk': scene_fandisk, 'fandisk-constrained': scene_fandisk_constrained,
          'joint-primitives': scene_joint_primitives, 'fandisk-filters': scene_fandisk_filters,
          'openfoam': scene_openfoam}


# ---------------------------------------------------------------------------------------------
# Comparing

def compare_arrays(a, b):
    """(values, differing values, largest absolute difference or None for strings) of two
    arrays, bit by bit (NaNs and signed zeros included); None when their shapes or types differ."""
    if a.shape != b.shape or a.dtype != b.dtype:
        return None
    if a.dtype.kind in 'fiub':
        bits = np.dtype('u%d' % a.dtype.itemsize)
        differing = a.view(bits) != b.view(bits)
        if a.dtype.kind == 'f':
            difference = np.abs(a.astype(np.float64) - b.astype(np.float64))[differing]
        else:
            difference = np.abs(a.astype(np.int64) - b.astype(np.int64))[differing]
        largest = float(np.nanmax(difference)) if np.any(~np.isnan(difference)) else (np.nan if difference.size else 0.0)
    else:  # strings: no difference to measure
        differing = a != b
        largest = None
    return a.size, int(np.count_nonzero(differing)), largest


def compare(folder_a, folder_b):
    """Prints every array of every scene saved in both folders with its differing values and
    largest absolute difference; returns the number of arrays that differ (or are missing)."""
    scenes = sorted({f[:-len('.pickle')] for d in (folder_a, folder_b) for f in os.listdir(d) if f.endswith('.pickle')})
    failures = total_arrays = total_values = 0
    print('%-90s %10s %10s %12s' % ('scene/output:port/array', 'values', 'differing', 'max|diff|'))
    for scene in scenes:
        saved = []
        for folder in (folder_a, folder_b):
            path = os.path.join(folder, scene + '.pickle')
            saved.append(pickle.load(open(path, 'rb')) if os.path.exists(path) else {})
        for key in sorted(set(saved[0]) | set(saved[1])):
            label = '%s/%s' % (scene, key)
            if key not in saved[0] or key not in saved[1]:
                print('%-90s only in %s' % (label, 'A' if key in saved[0] else 'B'))
                failures += 1
                continue
            result = compare_arrays(saved[0][key], saved[1][key])
            if result is None:
                print('%-90s shape or type differ: %s %s against %s %s' % (
                    label, saved[0][key].shape, saved[0][key].dtype, saved[1][key].shape, saved[1][key].dtype))
                failures += 1
                continue
            values, differing, largest = result
            print('%-90s %10d %10d %12s' % (label, values, differing, '-' if largest is None else '%.3g' % largest))
            failures += differing > 0
            total_arrays += 1
            total_values += values
    print('%d scenes, %d arrays, %d values compared: %s' % (
        len(scenes), total_arrays, total_values, 'IDENTICAL' if failures == 0 else '%d arrays DIFFER' % failures))
    return failures


def main():
    if sys.argv[1:2] == ['run'] and len(sys.argv) == 7:
        scene, plugin, data, case, work = sys.argv[2:7]
        os.makedirs(os.path.join(work, scene), exist_ok=True)
        arrays = {}
        SCENES[scene](arrays, plugin, data, case, os.path.join(work, scene))
        with open(os.path.join(work, scene + '.pickle'), 'wb') as f:
            pickle.dump(arrays, f)
        print('%s: %d arrays saved' % (scene, len(arrays)))
    elif sys.argv[1:2] == ['compare'] and len(sys.argv) == 4:
        sys.exit(1 if compare(sys.argv[2], sys.argv[3]) else 0)
    elif sys.argv[1:2] == ['scenes']:
        print(' '.join(SCENES))
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main()
