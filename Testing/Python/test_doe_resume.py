"""Issue 63 point 8: a design of experiments called on a pipeline that has not run yet (as a
ParaView user scripts it: Constraint Regions selecting patches by name, MLS Deform over them, no
update) takes its design's fingerprint from the updated pipeline, so that the same call again
resumes, in the same process and in a new one, and another design (other regions, other
settings) in the same folder is refused. Both on paraview.simple proxies and on the plain VTK
pipeline (vtkOpenFOAMReader, vtkConstraintRegion, vtkMLSDeformFilter).
Usage: pvpython test_doe_resume.py PLUGIN EXAMPLES_OPENFOAM_DIR WORK_DIR PVPYTHON
       (the script runs itself again as: ... PVPYTHON again, the call in a new process)"""
import json
import os
import subprocess
import sys

from paraview.simple import LoadPlugin

plugin, examples, work, pvpython = sys.argv[1:5]
again = sys.argv[5:] == ['again']
LoadPlugin(plugin, remote=False, ns=globals())
import mlsdeform  # noqa: E402
from mlsdeform.deformer import mesh_regions  # noqa: E402
from paraview import simple as pvs  # noqa: E402

from checks import check, finish, raises  # noqa: E402

case = os.path.join(work, 'case', 'case.foam')
ROLES = {'Handle': ['body'], 'Fixed': ['inlet', 'outlet'], 'Slip': ['ground', 'top', 'front', 'back']}
SAMPLES = 300


def proxy_pipeline(roles=ROLES, samples=SAMPLES):
    """MLS Deform over Constraint Regions made of paraview.simple proxies, never updated here."""
    reader = pvs.OpenFOAMReader(FileName=case)
    reader.UpdatePipelineInformation()
    reader.MeshRegions = mesh_regions(reader.MeshRegions.Available, sum(roles.values(), []))
    reader.Decomposepolyhedra = 0
    # ConstraintRegion and MLSDeform: LoadPlugin's constructors in globals()
    regions = [ConstraintRegion(Input=reader,  # noqa: F821
                                 Role=role, SelectionMode='Blocks', Blocks=patches)
               for role, patches in roles.items()]
    deformed = MLSDeform(Input=reader, Regions=regions, NumberOfSamples=samples)  # noqa: F821
    return deformed, regions[0]


def vtk_pipeline(roles=ROLES, samples=SAMPLES):
    """The same on the plain VTK pipeline, never updated here."""
    from vtkmodules.vtkIOGeometry import vtkOpenFOAMReader
    Region = mlsdeform._load_wrapping().vtkConstraintRegion
    reader = vtkOpenFOAMReader()
    reader.SetFileName(case)
    reader.SetDecomposePolyhedra(0)
    reader.UpdateInformation()
    chosen = mesh_regions([reader.GetPatchArrayName(i) for i in range(reader.GetNumberOfPatchArrays())], sum(roles.values(), []))
    for i in range(reader.GetNumberOfPatchArrays()):
        reader.SetPatchArrayStatus(reader.GetPatchArrayName(i), 1 if reader.GetPatchArrayName(i) in chosen else 0)
    deform = mlsdeform._load_wrapping().vtkMLSDeformFilter()
    deform.SetNumberOfSamples(samples)
    deform.SetInputConnection(0, reader.GetOutputPort())
    regions = []
    for role, patches in roles.items():
        region = Region()
        region.SetInputConnection(reader.GetOutputPort())
        region.SetRole(getattr(Region, role))
        region.SetSelectionMode(Region.Blocks)
        for name in patches:
            region.AddBlock(name)
        deform.AddRegionConnection(region.GetOutputPort())
        regions.append(region)
    return deform, regions[0], (reader, regions)   # the last keeps the pipeline's objects alive


def design(deformed, handle):
    dvs = mlsdeform.DesignVariables(deformed)
    dvs.addHandleDV('dx', handle, translate=[1, 0, 0], lower=-0.05, upper=0.05)
    dvs.addHandleDV('dz', handle, translate=[0, 0, 1], lower=0, upper=0.03)
    return dvs


def run(kind, folder, **changes):
    made = (proxy_pipeline if kind == 'proxies' else vtk_pipeline)(**changes)
    return mlsdeform.designOfExperiments(design(*made[:2]), folder, samples=2, seed=4, verbose=False)


def stamps(report):
    return [os.path.getmtime(r['path']) for r in report]


folders = {kind: os.path.join(work, kind) for kind in ('proxies', 'vtk')}
if again:
    # a new process: the same call resumes each folder, rewriting nothing
    for kind, folder in folders.items():
        with open(os.path.join(folder, 'stamps.json')) as f:
            before = json.load(f)
        report = run(kind, folder)
        check(stamps(report) == before and [r['seconds'] for r in report] == json.load(open(os.path.join(folder, 'seconds.json'))),
              '%s, a new process: the same call resumes (the variants kept, not rewritten)' % kind)
    finish()
    sys.exit(0)

subprocess.run(['bash', os.path.join(examples, 'make-case.sh'), os.path.dirname(case)], check=True, stdout=subprocess.DEVNULL)
for kind, folder in folders.items():
    report = run(kind, folder)
    check(len(report) == 2 and all(r['ok'] and os.path.exists(r['path']) for r in report),
          '%s, before any update: two variants written (%s)' % (kind, [r['path'] for r in report]))
    with open(os.path.join(folder, 'design.json')) as f:
        recorded = json.load(f)['deformation']
    counts = [r['points'] for r in recorded['regions']]
    check(recorded['NumberOfSamples'] is not None and recorded['case'] and all(c > 0 for c in counts),
          '%s: the fingerprint is taken from the updated pipeline (samples %s, region points %s, case %s)'
          % (kind, recorded['NumberOfSamples'], counts, recorded['case']))
    resumed = run(kind, folder)
    check(stamps(resumed) == stamps(report) and [r['seconds'] for r in resumed] == [r['seconds'] for r in report],
          '%s, the same process: the same call on a new pipeline resumes (the variants kept, not rewritten)' % kind)
    raises(lambda: run(kind, folder, roles=dict(ROLES, Handle=['top'], Slip=['ground', 'front', 'back'])),
           'holds another design', '%s: other regions in the same folder' % kind)
    raises(lambda: run(kind, folder, samples=SAMPLES + 100), 'holds another design', '%s: another NumberOfSamples' % kind)
    with open(os.path.join(folder, 'stamps.json'), 'w') as f:
        json.dump(stamps(report), f)
    with open(os.path.join(folder, 'seconds.json'), 'w') as f:
        json.dump([r['seconds'] for r in report], f)
fresh = subprocess.run([pvpython] + sys.argv[:5] + ['again'], capture_output=True, text=True)
sys.stdout.write(fresh.stdout)
check(fresh.returncode == 0, 'a new process resumes both designs (exit %d: %s)' % (fresh.returncode, fresh.stderr.strip()[-300:]))
finish()
