"""Issue 55, points 1 to 4 and 6: a structural engineer's loop on a CalculiX deck (and a Gmsh mesh) from pvpython.

A plate with two holes meshed by Gmsh into quadratic tetrahedra (C3D10), its mesh in an included
file: ParaView opens the deck with the Mesh File reader (not AVS UCD), its sets are arrays that
Constraint Regions select by name, MLS Deform moves a hole (midside nodes with the rest, the
elements measured at their corners and integration points), Save Data writes the variant deck
(the included mesh beside it, only node coordinates changed) and ccx runs on it. A design of
experiments on the deck (mlsdeform.designOfExperiments, and the command line mlsdeform-doe.py)
writes variant decks with an FEM verdict each, and resumes.

  pvpython test_structural_deck.py PLUGIN WORK
"""
import csv
import json
import os
import shutil
import subprocess
import sys

import numpy as np
from paraview import servermanager as sm
from paraview.simple import ExtractCellsByRegion, LoadPlugin, OpenDataFile, SaveData
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'Examples', 'Structural'))
import plate  # noqa: E402
from checks import check, finish  # noqa: E402

plugin, work = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
shutil.rmtree(work, ignore_errors=True)
source = os.path.join(work, 'source')
holes = ((3.0, 2.0, 0.8), (7.0, 2.0, 0.8))
plate.mesh_plate(source, holes=holes, size=0.6)
deck = plate.write_analysis(source)
before = plate.run_ccx(deck)


def field(proxy, name):
    array = sm.Fetch(proxy).GetFieldData().GetArray(name)
    return array.GetTuple1(0) if array else None


def node_lines(path):
    """The deck's *NODE data lines {id: (x, y, z)} and all its other lines, in order."""
    nodes, others, inside = {}, [], False
    with open(path) as f:
        for line in f:
            if line.startswith('*'):
                inside = line.upper().startswith('*NODE') and not line.upper().startswith('*NODE ')
                others.append(line)
            elif inside:
                values = line.split(',')
                nodes[int(values[0])] = tuple(float(v) for v in values[1:4])
            else:
                others.append(line)
    return nodes, others


# 1. The deck opens with the Mesh File reader; quadratic tetrahedra; the sets as 0/1 arrays.
reader = OpenDataFile(deck)
check(reader.GetXMLName() == 'MeshFileReader', 'a deck opens with the Mesh File reader (%s)' % reader.GetXMLName())
grid = sm.Fetch(reader)
source_nodes, source_other = node_lines(os.path.join(source, 'mesh.inp'))
elements, inside = 0, False
for line in open(os.path.join(source, 'mesh.inp')):
    inside = inside if not line.startswith('*') else line.upper().startswith('*ELEMENT')
    elements += inside and line[:1].isdigit()  # one element a line (Gmsh writes C3D10 on one)
types = {grid.GetCellType(c) for c in range(grid.GetNumberOfCells())}
check(grid.GetNumberOfPoints() == len(source_nodes) and grid.GetNumberOfCells() == elements and types == {24},
      'every node and every C3D10 element, as VTK quadratic tetrahedra (%d points, %d cells, types %s)'
      % (grid.GetNumberOfPoints(), grid.GetNumberOfCells(), types))
ids = vtk_to_numpy(grid.GetPointData().GetArray('NodeId'))
for name in ('fixed', 'load', 'hole1', 'hole2'):
    array = grid.GetPointData().GetArray(name)
    members = set(plate.node_set(os.path.join(source, 'mesh.inp'), name))
    check(array is not None and set(ids[vtk_to_numpy(array) == 1]) == members,
          'node set %s is a point array, 1 on its %d nodes' % (name, len(members)))
check(grid.GetCellData().GetArray('part') is not None, 'element set part is a cell array')
x = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)

# 2. Regions by set name (Sets, the panel's list of the deck's sets, or Blocks entries): the ends
# fixed, hole1 moved along x; the elements stay valid.
fixed = ConstraintRegion(Input=reader, Role='Fixed', SelectionMode='Blocks', Sets=['fixed', 'load'])
fixed.UpdatePipeline()
domain = fixed.GetProperty('Sets').SMProperty.GetDomain('array_list')
listed = {domain.GetString(i) for i in range(domain.GetNumberOfStrings())}
check({'fixed', 'load', 'hole1', 'hole2', 'part'} <= listed and not listed & {'NodeId', 'ElementId'},
      'the panel\'s Sets list holds the deck\'s sets, not its ids: %s' % sorted(listed))
hole = ConstraintRegion(Input=reader, Role='Handle', SelectionMode='Blocks', Blocks=['hole1'])
hole.Translation = [0.4, 0, 0]
deform = MLSDeform(Input=reader, Regions=[fixed, hole])
out = sm.Fetch(deform)
moved = vtk_to_numpy(out.GetPoints().GetData()).astype(float)
in_hole = vtk_to_numpy(grid.GetPointData().GetArray('hole1')) == 1
in_fixed = vtk_to_numpy(grid.GetPointData().GetArray('fixed')) == 1
shift = moved - x
# the handle's and the fixed regions' misfit: the penalty balance of test_proxies, (stretch + bend)
# / fix weight of the motion (0.4)
balance = (deform.StretchWeight + deform.BendWeight) / deform.FixWeight * 0.4
check(np.abs(shift[in_hole] - [0.4, 0, 0]).max() < balance and np.abs(shift[in_fixed]).max() < balance,
      'the hole moves by 0.4 along x, the clamped end stays (within the balance %.2g)' % balance)
check(field(deform, 'MaxNonOrthogonality') is None and field(deform, 'MaxSkewness') is None,
      'a deck gets the FEM solver\'s verdict: no checkMesh face measures')
check(field(deform, 'InvertedCells') == 0 and 0 < field(deform, 'MinScaledJacobian') <= 1,
      'no element inverted at its corners or integration points; least scaled Jacobian %.3f (before %.3f)'
      % (field(deform, 'MinScaledJacobian'), field(deform, 'OriginalMinScaledJacobian')))

# 3. Save Data writes the variant deck: its include beside it, only the node coordinates changed.
variant = os.path.join(work, 'variant', 'plate.inp')
SaveData(variant, proxy=deform)
check(open(variant, 'rb').read() == open(deck, 'rb').read(), 'the main deck is copied byte for byte')
variant_nodes, variant_other = node_lines(os.path.join(work, 'variant', 'mesh.inp'))
check(variant_other == source_other, 'every line of the included mesh but the nodes\' is byte-identical')
by_id = dict(zip(ids.tolist(), map(tuple, moved)))
# exactly, or within 1e-13 where the shortest text of a coordinate is wider than the 20 characters
# CalculiX reads a number in (14 significant digits then)
check(sorted(variant_nodes) == sorted(source_nodes) and
      all(abs(a - b) <= 1e-13 * abs(b) for n in variant_nodes for a, b in zip(variant_nodes[n], by_id[n])),
      'the variant\'s nodes are the same ids at the deformed positions')
unmoved = [n for n in source_nodes if by_id[n] == source_nodes[n]]


def node_text(path):
    lines = open(path).read().split('*NODE\n', 1)[1].split('*', 1)[0].splitlines()
    return {int(line.split(',')[0]): line for line in lines}


source_text, variant_text = node_text(os.path.join(source, 'mesh.inp')), node_text(os.path.join(work, 'variant', 'mesh.inp'))
check(all(variant_text[n] == source_text[n] for n in unmoved), 'unmoved nodes keep their text (%d)' % len(unmoved))

# 4. ccx runs on the variant: the same load nodes, a changed but close deflection.
after = plate.run_ccx(variant)
tip = lambda u: np.mean([v[2] for v in u.values()])  # noqa: E731
check(sorted(after) == sorted(before) and tip(after) != tip(before) and abs(tip(after) / tip(before) - 1) < 0.2,
      'ccx runs on the variant: mean tip deflection %.5f mm (source %.5f)' % (tip(after), tip(before)))

# 5. Nothing is written over the source, or from data that did not come from the deck.
stamp = os.stat(deck).st_mtime_ns, open(os.path.join(source, 'mesh.inp'), 'rb').read()
SaveData(deck, proxy=deform, Overwrite=1)
check((os.stat(deck).st_mtime_ns, open(os.path.join(source, 'mesh.inp'), 'rb').read()) == stamp,
      'saving onto the source deck is refused and changes nothing')
part = ExtractCellsByRegion(Input=deform)
part.IntersectWith = 'Plane'
part.IntersectWith.Origin = [5, 0, 0]
other = os.path.join(work, 'part', 'plate.inp')
SaveData(other, proxy=part)
check(not os.path.exists(os.path.join(work, 'part')) or not os.listdir(os.path.join(work, 'part')),
      'half the mesh (other node count) is refused: nothing written')

# 6. The same part as a Gmsh mesh (.msh 4.1 binary and 2.2 ASCII): its physical groups are the sets,
# Save Data writes a .msh variant that Gmsh reads, with the deformed positions exactly.
for version, binary in (('msh41', True), ('msh22', False)):
    mesh = os.path.join(work, 'gmsh', version, 'plate.msh')
    os.makedirs(os.path.dirname(mesh), exist_ok=True)
    subprocess.run(['gmsh', '-3', os.path.join(source, 'plate.geo'), '-format', version, '-o', mesh] + (['-bin'] if binary else []),
                   check=True, stdout=subprocess.DEVNULL)
    msh = OpenDataFile(mesh)
    kind = '%s %s' % (version, 'binary' if binary else 'ASCII')
    check(msh.GetXMLName() == 'MeshFileReader' and {24} == {sm.Fetch(msh).GetCellType(c) for c in range(sm.Fetch(msh).GetNumberOfCells())},
          '%s opens with the Mesh File reader into quadratic tetrahedra' % kind)
    fixed_m = ConstraintRegion(Input=msh, Role='Fixed', SelectionMode='Blocks', Sets=['fixed', 'load'])
    hole_m = ConstraintRegion(Input=msh, Role='Handle', SelectionMode='Blocks', Sets=['hole1'], Translation=[0.4, 0, 0])
    deform_m = MLSDeform(Input=msh, Regions=[fixed_m, hole_m])
    moved_m = vtk_to_numpy(sm.Fetch(deform_m).GetPoints().GetData()).astype(float)
    ids_m = vtk_to_numpy(sm.Fetch(msh).GetPointData().GetArray('NodeId'))
    target = os.path.join(work, 'gmsh', version, 'variant', 'plate.msh')
    SaveData(target, proxy=deform_m)
    reread = subprocess.run(['gmsh', target, '-0', '-o', os.path.join(work, 'gmsh', version, 'reread.msh')], capture_output=True, text=True)
    back = sm.Fetch(OpenDataFile(target))
    same = dict(zip(vtk_to_numpy(back.GetPointData().GetArray('NodeId')).tolist(), map(tuple, vtk_to_numpy(back.GetPoints().GetData()))))
    check(reread.returncode == 0 and 'Error' not in reread.stdout + reread.stderr and
          all(same[n] == tuple(p) for n, p in zip(ids_m.tolist(), moved_m)),
          '%s: the variant has the deformed positions exactly and Gmsh reads it' % kind)

# 7. A design of experiments on the deck: variant decks with the FEM verdict, resumable.
import mlsdeform  # noqa: E402
hole.Translation = [0, 0, 0]
dvs = mlsdeform.DesignVariables(deform)
dvs.addHandleDV('x1', [hole], translate=[1, 0, 0], lower=-0.5, upper=0.5)
doe = os.path.join(work, 'doe')
rows = mlsdeform.designOfExperiments(dvs, doe, samples=3, seed=1, verbose=False)
check([sorted(r) for r in rows] == [sorted(['variant', 'x1', 'InvertedCells', 'MinScaledJacobian', 'ok', 'seconds', 'path'])] * 3,
      'the report has the FEM verdict\'s figures: InvertedCells, MinScaledJacobian')
check(all(r['ok'] == (r['InvertedCells'] == 0 and r['MinScaledJacobian'] >= mlsdeform.FEM_THRESHOLDS['MinScaledJacobian'])
          for r in rows) and all(r['ok'] for r in rows),
      'every variant passes the FEM thresholds (least scaled Jacobians %s)' % [round(r['MinScaledJacobian'], 3) for r in rows])
check(all(r['path'] == os.path.join(doe, r['variant'], 'plate.inp') and os.path.exists(os.path.join(doe, r['variant'], 'mesh.inp'))
          for r in rows), 'each variant is a deck with its included mesh: variant<i>/plate.inp, mesh.inp')
u = plate.run_ccx(rows[0]['path'])
check(sorted(u) == sorted(before), 'ccx runs on a variant of the design of experiments')
stamps = [os.stat(r['path']).st_mtime_ns for r in rows]
again = mlsdeform.designOfExperiments(dvs, doe, samples=3, seed=1, verbose=False)
check([r['variant'] for r in again] == [r['variant'] for r in rows] and
      [os.stat(r['path']).st_mtime_ns for r in again] == stamps, 'running it again resumes: nothing rewritten')
strict = mlsdeform.designOfExperiments(dvs, os.path.join(work, 'strict'), samples=2, verbose=False,
                                       thresholds={'MinScaledJacobian': 0.99})
check(not any(r['ok'] or r['path'] for r in strict), 'a threshold above every variant\'s figure fails them: reported, not written')
try:
    mlsdeform.designOfExperiments(dvs, os.path.join(work, 'bad'), samples=2, verbose=False, thresholds={'MaxSkewness': 4})
    check(False, 'a case\'s threshold on a deck is an error')
except ValueError as e:
    check('MaxSkewness' in str(e) and 'MinScaledJacobian' in str(e), 'a case\'s threshold on a deck is an error: %s' % e)

# 8. The command line on a deck design: the sets by name, the same verdicts.
design = os.path.join(work, 'design.json')
with open(design, 'w') as f:
    json.dump({'deck': 'source/plate.inp', 'handle': ['hole1'], 'fixed': ['fixed', 'load'],
               'variables': [{'name': 'x1', 'translate': [1, 0, 0], 'lower': -0.5, 'upper': 0.5}]}, f)
script = os.path.join(os.path.dirname(plugin), 'mlsdeform-doe.py')
run = subprocess.run(['/usr/bin/python3', script, design, os.path.join(work, 'cli'), '--samples', '2'],
                     capture_output=True, text=True)
with open(os.path.join(work, 'cli', 'report.csv')) as f:
    table = list(csv.DictReader(f))
check(run.returncode == 0 and len(table) == 2 and all(r['ok'] == 'True' and os.path.exists(r['path']) for r in table) and
      'MinScaledJacobian' in table[0], 'mlsdeform-doe.py on a deck writes 2 variant decks with their verdicts (%s)'
      % (run.stderr.strip()[-300:] or run.stdout.strip().splitlines()[-1]))
finish()
