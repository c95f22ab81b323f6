"""Issue 30 point 3: mlsdeform.designOfExperiments on the sphereChannel snappyHexMesh case (built
here): a Latin hypercube and a table into variant cases with a mesh-quality verdict each, the
report, the thresholds, resuming after an interruption, and bad designs.
Usage: pvpython test_design_of_experiments.py PLUGIN EXAMPLES_OPENFOAM_DIR WORK_DIR PYTHON3"""
import csv
import os
import re
import shutil
import subprocess
import sys

import numpy as np
from paraview.simple import LoadPlugin
from vtkmodules.vtkCommonCore import vtkLogger

plugin, examples, work, python3 = sys.argv[1:5]
LoadPlugin(plugin, remote=False)
sys.path.insert(0, examples)
import mlsdeform  # noqa: E402
import openfoam_variant  # noqa: E402

from checks import check, finish, raises  # noqa: E402


case = os.path.join(work, 'case')
subprocess.run(['bash', os.path.join(examples, 'make-case.sh'), case], check=True)
handle, fixed, slip = ['body'], ['inlet', 'outlet'], ['ground', 'top', 'front', 'back']
log = os.path.join(work, 'first-variant.log')
vtkLogger.LogToFile(log, vtkLogger.TRUNCATE, vtkLogger.VERBOSITY_TRACE)
reader = openfoam_variant.open_case(os.path.join(case, 'case.foam'), handle + fixed + slip, decompose_polyhedra=False)
deformed = openfoam_variant.morph(reader, handle, (0, 0, 0), fixed, slip)
vtkLogger.EndLogToFile(log)
with open(log) as f:
    text = f.read()
check("the case's faces read ahead" in text and "the case's cells against the grid's" in text,
      "in a builtin session open_case reads the case's faces ahead, and MLS Deform's mesh quality takes them")
body = deformed.Regions[0]
dvs = mlsdeform.DesignVariables(deformed)
dvs.addHandleDV('dx', body, translate=[1, 0, 0], lower=-0.05, upper=0.05)
dvs.addHandleDV('dz', body, translate=[0, 0, 1], lower=0, upper=0.03)
dvs.addHandleDV('yaw', body, rotate=[0, 0, 1], lower=-10, upper=10)
names = dvs.getVarNames()

# A Latin hypercube: one point in each of N strata of every variable's range
points = mlsdeform.latinHypercube([(-1, 1), (0, 3)], 8, seed=3)
strata = np.floor((points - [-1, 0]) / [2, 3] * 8).astype(int)
check(all(sorted(strata[:, j]) == list(range(8)) for j in range(2)), 'a Latin hypercube has one point in each stratum')
check(np.array_equal(points, mlsdeform.latinHypercube([(-1, 1), (0, 3)], 8, seed=3)), 'the same seed gives the same points')

variants = os.path.join(work, 'lhs')
report = mlsdeform.designOfExperiments(dvs, variants, samples=4, seed=1)
check(len(report) == 4 and all(r['ok'] and os.path.exists(r['path']) for r in report),
      'four variants pass the default thresholds and are written (%s)' % [r['path'] for r in report])
with open(os.path.join(variants, 'report.csv')) as f:
    rows = list(csv.DictReader(f))
check(len(rows) == 4 and set(names + ['InvertedCells', 'MaxNonOrthogonality', 'MaxSkewness', 'ok', 'seconds', 'path']) <= set(rows[0]),
      'report.csv: a row per variant with the values, the quality, the verdict, seconds and path')
check(all(float(rows[i][n]) == report[i][n] for i in range(4) for n in names), 'report.csv holds the values exactly')
check(dvs.getValues() == {'dx': 0.0, 'dz': 0.0, 'yaw': 0.0}, 'the design values are restored afterwards')
check(openfoam_variant.checkmesh(os.path.dirname(report[0]['path']))[0], 'checkMesh passes on a variant')
moved = open(os.path.join(os.path.dirname(report[0]['path']), 'constant', 'polyMesh', 'points')).read()
check(moved != open(os.path.join(case, 'constant', 'polyMesh', 'points')).read(), "a variant's points differ from the source's")

# disk-lean variants: the variant's own points, links to the source's unchanged files
variant = os.path.dirname(report[0]['path'])
faces = os.path.join(variant, 'constant', 'polyMesh', 'faces')
check(os.path.islink(faces) and os.path.realpath(faces) == os.path.realpath(os.path.join(case, 'constant', 'polyMesh', 'faces')),
      "a variant links the source's unchanged files (constant/polyMesh/faces)")
points_file = os.path.join(variant, 'constant', 'polyMesh', 'points')
check(os.path.isfile(points_file) and not os.path.islink(points_file), 'a variant holds its own points file')
own = sum(os.lstat(os.path.join(d, f)).st_size for d, _, files in os.walk(variant) for f in files
          if not os.path.islink(os.path.join(d, f)))
check(own <= 1.2 * os.path.getsize(points_file), "a variant's own files: %d bytes, the points file %d (issue 30: within 1.2x)"
      % (own, os.path.getsize(points_file)))


def snapshot(folder):
    return {os.path.join(d, f): (os.lstat(os.path.join(d, f)).st_mtime_ns, os.lstat(os.path.join(d, f)).st_size)
            for d, _, files in os.walk(folder) for f in files}


before = snapshot(case)
run = subprocess.run(['bash', '-c', 'source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1; simpleFoam -case "%s"' % variant],
                     capture_output=True, text=True)
check(run.returncode == 0 and os.path.isdir(os.path.join(variant, '20')) and 'End' in run.stdout,
      'simpleFoam runs on a linked variant and writes its time folder there (exit %d)' % run.returncode)
check(snapshot(case) == before, 'the source case is untouched by the run')
copied = mlsdeform.designOfExperiments(dvs, os.path.join(work, 'copies'), samples=1, seed=1, copy=True, verbose=False)
check(not any(os.path.islink(os.path.join(d, f)) for d, _, files in os.walk(os.path.dirname(copied[0]['path'])) for f in files),
      'copy=True writes a self-contained case')

# resuming: a variant interrupted while it was written (its .writing- folder) is written again,
# the complete ones are kept as they are
second = os.path.dirname(report[2]['path'])
os.rename(second, second + '.writing-12345')
first_time = os.path.getmtime(report[0]['path'])
again = mlsdeform.designOfExperiments(dvs, variants, samples=4, seed=1)
check(os.path.exists(report[2]['path']) and not os.path.exists(second + '.writing-12345'),
      'the interrupted variant is written again and its partial folder removed')
check(os.path.getmtime(report[0]['path']) == first_time and again[0]['seconds'] == report[0]['seconds'],
      'complete variants are kept (not rewritten)')
check([r['path'] for r in again] == [r['path'] for r in report], 'the resumed report lists the same variants')
raises(lambda: mlsdeform.designOfExperiments(dvs, variants, samples=5, seed=1), 'holds another design',
       'another design in the same folder')
own = os.path.join(work, 'own-design')  # the folder of the user's own design file for mlsdeform-doe.py
os.makedirs(own, exist_ok=True)
with open(os.path.join(own, 'design.json'), 'w') as f:
    f.write('{"case": "case/case.foam", "handle": ["body"], "variables": []}')
raises(lambda: mlsdeform.designOfExperiments(dvs, own, samples=2), "is not a design of experiments' record",
       'variants into the folder of a design file')

# the thresholds: a variant over them is reported and not written, unless asked
strict = mlsdeform.designOfExperiments(dvs, os.path.join(work, 'strict'), samples=2, seed=1,
                                       thresholds={'MaxNonOrthogonality': 1.0}, verbose=False)
check(all(not r['ok'] and r['path'] == '' and r['MaxNonOrthogonality'] > 1 for r in strict),
      'variants over a threshold are reported (ok False) and not written')
check(not any(name.startswith('variant') for name in os.listdir(os.path.join(work, 'strict'))), 'no variant folder was written')
kept = mlsdeform.designOfExperiments(dvs, os.path.join(work, 'strict-kept'), samples=1, seed=1,
                                     thresholds={'MaxNonOrthogonality': 1.0}, writeFailed=True, verbose=False)
check(not kept[0]['ok'] and os.path.exists(kept[0]['path']), 'writeFailed writes a failing variant too')

# a table of values (columns in any order)
table = os.path.join(work, 'doe.csv')
with open(table, 'w') as f:
    f.write('yaw,dx,dz\n5,0.01,0.02\n-5,-0.02,0\n')
tabled = mlsdeform.designOfExperiments(dvs, os.path.join(work, 'table'), table=table, verbose=False)
check([(r['dx'], r['dz'], r['yaw']) for r in tabled] == [(0.01, 0.02, 5.0), (-0.02, 0.0, -5.0)], 'a table gives its rows as variants')
for text, message, what in (('dx,dz\n0,0\n', 'are not the design variables', 'a missing column'),
                            ('dx,dz,yaw,drag\n0,0,0,1\n', 'are not the design variables', 'an unknown column'),
                            ('dx,dz,yaw\n0,0.1,0\n', 'row 2, column dz', 'a value outside its bounds'),
                            ('dx,dz,yaw\n0,zero,0\n', 'is not a number', 'a value that is no number'),
                            ('dx,dz,yaw\n', 'has no rows', 'no rows')):
    with open(table, 'w') as f:
        f.write(text)
    raises(lambda: mlsdeform.designOfExperiments(dvs, os.path.join(work, 'bad'), table=table), message, 'a table with ' + what)
raises(lambda: mlsdeform.designOfExperiments(dvs, os.path.join(work, 'bad'), samples=3, table=table), 'not both', 'samples and a table')
raises(lambda: mlsdeform.designOfExperiments(dvs, os.path.join(work, 'bad'), samples=0), 'positive integer', 'no samples')
raises(lambda: mlsdeform.designOfExperiments(dvs, os.path.join(work, 'bad'), samples=2, thresholds={'Volume': 1}),
       'unknown threshold', 'an unknown threshold')

# A mesh whose quality cannot be measured: a face shared by three cells (as ParaView's OpenFOAM
# reader makes with Decompose polyhedra on). MeshQuality is on; the verdict's error names the cause
# and what to change, not "turn MeshQuality on".
from paraview import servermanager  # noqa: E402
from paraview.simple import MLSDeform, ConstraintRegion  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import VTK_TETRA, vtkUnstructuredGrid  # noqa: E402
fan = vtkUnstructuredGrid()
fan_points = vtkPoints()
for p in ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0.3, 0.3, 1), (0.3, 0.3, -1), (0.2, 0.2, 2)):
    fan_points.InsertNextPoint(p)
fan.SetPoints(fan_points)
for apex in (3, 4, 5):
    fan.InsertNextCell(VTK_TETRA, 4, [0, 1, 2, apex])
producer = servermanager.sources.PVTrivialProducer()
producer.GetClientSideObject().SetOutput(fan)
tip = ConstraintRegion(Input=producer, Role='Handle', Translation=[0.05, 0, 0])
tip.Region = 'Sphere'
tip.Region.Center, tip.Region.Radius = [0.2, 0.2, 2], 0.1
foot = ConstraintRegion(Input=producer, Role='Fixed')
foot.Region = 'Sphere'
foot.Region.Center, foot.Region.Radius = [0.3, 0.3, -1], 0.1
fan_deform = MLSDeform(Input=producer, Regions=[foot, tip], NumberOfSamples=20)
fan_deform.UpdatePipeline()
try:
    mlsdeform.meshQuality(mlsdeform.DesignVariables(fan_deform))
    raised = ''
except RuntimeError as error:
    raised = str(error)
check('more than two cells' in raised and 'Decompose polyhedra' in raised and 'MeshQuality on' not in raised,
      'a mesh MLS Deform cannot measure: the verdict\'s error names the cause: "%s"' % raised)

# the command line: a design file (relative case path), a Latin hypercube, a progress line per
# variant, the report; in Debian's python3 (a plain VTK pipeline, mlsdeform.vtkfoam) and in pvpython
# the same variants as the package's designOfExperiments on paraview.simple proxies, bit for bit;
# a bad design file exits with 2 and the message
import json  # noqa: E402
design = os.path.join(work, 'design.json')
variables = [{'name': 'dx', 'translate': [1, 0, 0], 'lower': -0.05, 'upper': 0.05},
             {'name': 'yaw', 'rotate': [0, 0, 1], 'lower': -10, 'upper': 10}]
with open(design, 'w') as f:
    json.dump({'case': 'case/case.foam', 'handle': handle, 'fixed': fixed, 'slip': slip, 'variables': variables,
               'settings': {'NumberOfSamples': 500}}, f)
command = [os.path.join(os.path.dirname(plugin), 'mlsdeform-doe.py'), design, None, '--samples', '3', '--seed', '2']
reports = {}
for interpreter in (python3, 'pvpython'):
    folder = os.path.join(work, 'cli-' + os.path.basename(interpreter))
    command[2] = folder
    run = subprocess.run([interpreter] + command, capture_output=True, text=True)
    check(run.returncode == 0 and len(re.findall(r'^variant\d+ \(\d+ of 3\)', run.stdout, re.M)) == 3 and
          '3 variants, 3 pass the thresholds' in run.stdout,
          'the command line in %s writes 3 variants with a progress line each (exit %d: %s)'
          % (interpreter, run.returncode, run.stdout[-300:] + run.stderr[-300:]))
    with open(os.path.join(folder, 'report.csv')) as f:
        reports[interpreter] = list(csv.DictReader(f))
    check(len(reports[interpreter]) == 3, "the command line's report.csv has 3 rows")
proxies = openfoam_variant.morph(reader, handle, (0, 0, 0), fixed, slip, NumberOfSamples=500)
same = mlsdeform.DesignVariables(proxies)
for v in variables:
    same.addHandleDV(v['name'], proxies.Regions[0], lower=v['lower'], upper=v['upper'],
                     **{k: v[k] for k in ('translate', 'rotate') if k in v})
expected = mlsdeform.designOfExperiments(same, os.path.join(work, 'cli-proxies'), samples=3, seed=2, verbose=False)
columns = ['variant', 'dx', 'yaw', 'InvertedCells', 'MaxNonOrthogonality', 'MaxSkewness', 'ok']
for interpreter, rows in reports.items():
    check([[r[c] for c in columns] for r in rows] == [[str(e[c]) if not isinstance(e[c], float) else repr(e[c]) for c in columns]
                                                         for e in expected],
          "the command line's report in %s is the package's on proxies (values, quality figures, verdicts)" % interpreter)
    check(all(open(os.path.join(os.path.dirname(r['path']), 'constant', 'polyMesh', 'points'), 'rb').read() ==
              open(os.path.join(os.path.dirname(e['path']), 'constant', 'polyMesh', 'points'), 'rb').read()
              for r, e in zip(rows, expected)),
          "and its variants' points files are the proxies', byte for byte (%s)" % interpreter)
with open(design, 'w') as f:
    json.dump({'case': 'case/case.foam', 'handle': ['hull'], 'variables': []}, f)
run = subprocess.run([python3] + command, capture_output=True, text=True)
check(run.returncode == 2 and 'has no patch or patch group hull' in run.stderr and 'its patches: inlet' in run.stderr,
      'a design naming a patch the case lacks exits with 2, naming the case\'s patches (%s)' % run.stderr.strip()[-200:])

# issue 54, point 4: the same design by patterns and a patch group, its handle named as a body
# ("handles"), run from a python3 that lacks numpy and VTK (here Debian's without its site
# packages, -S): it hands itself to Debian's python3 and writes the same variants
with open(design, 'w') as f:
    json.dump({'case': 'case/case.foam', 'handles': {'sphere': ['bod.*']}, 'fixed': ['in.*', 'outlet'],
               'slip': ['ground', 'top', 'front', 'back'], 'variables': [dict(v, handles=['sphere']) for v in variables],
               'settings': {'NumberOfSamples': 500}}, f)
command[2] = os.path.join(work, 'cli-patterns')
run = subprocess.run([python3, '-S'] + command, capture_output=True, text=True)
with open(os.path.join(work, 'cli-patterns', 'report.csv')) as f:
    patterns = list(csv.DictReader(f))
check(run.returncode == 0 and [[r[c] for c in columns] for r in patterns] == [[r[c] for c in columns] for r in reports[python3]],
      'patterns, a named body and a python3 without numpy give the same variants (exit %d: %s)'
      % (run.returncode, run.stderr.strip()[-300:]))
# another design in a folder that holds one: refused, saying what differs (here the handle's
# patches, which change the regions), and nothing of the folder is touched
with open(design, 'w') as f:
    json.dump({'case': 'case/case.foam', 'handle': ['top'], 'fixed': fixed, 'slip': ['ground', 'front', 'back'],
               'variables': variables, 'settings': {'NumberOfSamples': 500}}, f)
command[2] = os.path.join(work, 'cli-patterns')
before = open(os.path.join(work, 'cli-patterns', 'report.csv')).read()
run = subprocess.run([python3] + command, capture_output=True, text=True)
check(run.returncode == 2 and 'holds another design' in run.stderr and 'deformation' in run.stderr and
      open(os.path.join(work, 'cli-patterns', 'report.csv')).read() == before,
      'another design into the same folder is refused, naming what differs (%s)' % run.stderr.strip()[-200:])
command[2] = os.path.join(work, 'cli-bad')
for bad, message in (({'handle': ['wall'], 'slip': ['ground', 'top']}, 'ground is in handle and in slip'),
                     ({'handle': handle, 'handles': {'a': handle}}, "either 'handle'"),
                     ({'handles': {'a': []}}, "maps each body's name"),
                     ({'handle': handle, 'variables': [dict(variables[0], patches=['body'])]}, "move as one body now"),
                     ({'handle': handle, 'variables': [dict(variables[0], handles=['wing'])]}, "names the bodies ['wing']"),
                     ({'handle': handle, 'slipp': slip}, "unknown key 'slipp' (did you mean 'slip'?)"),
                     ({'handle': handle, 'variables': [{'name': 'dx', 'translate': [1, 0, 0]}]},
                      "design variable 'dx' has no lower and upper bound")):
    with open(design, 'w') as f:
        json.dump(dict({'case': 'case/case.foam', 'variables': variables}, **bad), f)
    run = subprocess.run([python3] + command, capture_output=True, text=True)
    check(run.returncode == 2 and message in run.stderr, 'a design with %s exits with 2 (%s)' % (list(bad), run.stderr.strip()[-200:]))
with open(design, 'w') as f:
    f.write('{"case": "case/case.foam", }')
run = subprocess.run([python3] + command, capture_output=True, text=True)
check(run.returncode == 2 and 'design.json: not JSON' in run.stderr, 'a design file that is not JSON exits with 2, naming it (%s)' %
      run.stderr.strip()[-200:])
# settings: an enumeration value by its VTK name; an unknown name or property exits with 2
with open(design, 'w') as f:
    json.dump({'case': 'case/case.foam', 'handle': handle, 'fixed': fixed, 'slip': slip, 'variables': variables,
               'settings': {'NumberOfSamples': 500, 'Basis': 'Wendland'}}, f)
command[2] = os.path.join(work, 'cli-wendland')
run = subprocess.run([python3] + command, capture_output=True, text=True)
with open(os.path.join(work, 'cli-wendland', 'report.csv')) as f:
    wendland = list(csv.DictReader(f))
check(run.returncode == 0 and [r['MaxNonOrthogonality'] for r in wendland] != [r['MaxNonOrthogonality'] for r in reports[python3]],
      "a setting by its enumeration name: Basis 'Wendland' deforms otherwise (exit %d)" % run.returncode)
for settings, message in (({'Basis': 'Linear'}, 'neither a number nor a name'), ({'Bassis': 0}, 'has no setting Bassis')):
    with open(design, 'w') as f:
        json.dump({'case': 'case/case.foam', 'handle': handle, 'variables': variables, 'settings': settings}, f)
    run = subprocess.run([python3] + command, capture_output=True, text=True)
    check(run.returncode == 2 and message in run.stderr, 'a bad setting %s exits with 2 (%s)' % (settings, run.stderr.strip()[-200:]))

# issue 66 point 6: a Latin hypercube over local shape variables (four control points on the
# sphere along its normals) from the design file; a local variable on two bodies is refused
with open(design, 'w') as f:
    json.dump({'case': 'case/case.foam', 'handle': handle, 'fixed': fixed, 'slip': slip, 'settings': {'NumberOfSamples': 500},
               'variables': [{'name': 'bump', 'local': {'count': 4}, 'lower': -0.002, 'upper': 0.002}]}, f)
command[2] = os.path.join(work, 'cli-local')
run = subprocess.run([python3] + command, capture_output=True, text=True)
with open(os.path.join(work, 'cli-local', 'report.csv')) as f:
    local = list(csv.DictReader(f))
check(run.returncode == 0 and '3 variants, 3 pass the thresholds' in run.stdout and
      all(len({r['bump_%d' % i] for r in local}) == 3 for i in range(4)),
      'a design of local variables (bump_0 .. bump_3) gives 3 variants, each variable at 3 levels (exit %d: %s)'
      % (run.returncode, run.stdout[-200:] + run.stderr[-300:]))
# ... and from Python: designOfExperiments over local variables of a deformation of their own
local_deformed = openfoam_variant.morph(reader, handle, (0, 0, 0), fixed, slip, NumberOfSamples=500)
local_dvs = mlsdeform.DesignVariables(local_deformed)
bumps = local_dvs.addLocalDV('bump', local_deformed.Regions[0], count=4, lower=-0.002, upper=0.002)
local_report = mlsdeform.designOfExperiments(local_dvs, os.path.join(work, 'lhs-local'), samples=3, seed=2, verbose=False)
strata = np.array([[np.floor((r[b] + 0.002) / 0.004 * 3) for b in bumps] for r in local_report])
check(len(local_report) == 3 and all(r['ok'] and os.path.exists(r['path']) for r in local_report) and
      all(sorted(strata[:, j]) == [0, 1, 2] for j in range(4)) and local_dvs.getValues() == dict.fromkeys(bumps, 0.0),
      'designOfExperiments over 4 local variables: 3 variants written, each variable once in each third of its range, '
      'the values restored')
with open(design, 'w') as f:
    json.dump({'case': 'case/case.foam', 'handles': {'a': handle, 'b': ['top']}, 'variables':
               [{'name': 'bump', 'local': {'count': 4}, 'lower': -0.002, 'upper': 0.002}]}, f)
command[2] = os.path.join(work, 'cli-bad')
run = subprocess.run([python3] + command, capture_output=True, text=True)
check(run.returncode == 2 and 'acts on one body' in run.stderr, 'local variables on two bodies exit with 2 (%s)' % run.stderr.strip()[-200:])


# The README's design of experiments (its Tour 3) runs as written, but for its paths
readme = open(os.path.join(examples, '..', '..', 'README.md')).read()
snippet = re.search(r"```python\n(from paraview.simple import LoadPlugin\n.*?designOfExperiments.*?)```", readme, re.S).group(1)
readme_work = os.path.join(work, 'readme-doe')
snippet = snippet.replace('build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so', plugin).replace(
    '/tmp/sphere/case.foam', os.path.join(case, 'case.foam')).replace('/tmp/sphere-doe', readme_work)
namespace = {}
exec(snippet, namespace)
check(len(namespace['report']) == 3 and all(os.path.exists(os.path.join(os.path.dirname(r['path']), 'constant', 'polyMesh', 'points'))
                                              for r in namespace['report'] if r['ok']) and
      os.path.exists(os.path.join(readme_work, 'report.csv')), "the README's design of experiments runs as written: %s" %
      [(r['variant'], r['ok']) for r in namespace['report']])

finish()
