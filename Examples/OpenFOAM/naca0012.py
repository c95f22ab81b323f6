"""The NACA 0012 laminar drag case of OpenFOAM's adjoint tutorials (make-naca0012-case.sh) as a
design problem, for the adjoint examples: its deformation with two design variables on the
airfoil, and adjointOptimisationFoam runs on its variants. Load the plugin before importing this.

The airfoil (patches pressure and suction, one Handle region) turns and thickens about its quarter
chord; the far field (patch inlet) is Fixed; the front and back planes (patch frontBack, type empty)
are two Slip regions, and the deformation is that of a 2D case extruded along z (MLS Deform's
ExtrusionAxis): both planes move alike, so the mesh stays 2D (Slip regions alone keep each plane
flat but let them drift apart in x and y, which checkMesh reports as non-aligned edges):
  aoa        Rotate about -z (nose up), in degrees, -3 to 3
  thickness  Scale along y: the thickness grows by the factor 1 + thickness, -0.3 to 0.3
J is the tutorial's drag objective (force along the flow direction, over 0.5 UInf^2 Aref, kinematic).

shape_deformation(foam_file, stations) gives the airfoil's local shape variables instead: the upper
(suction) and lower (pressure) surfaces each a Handle region of their own, with a control point at
each chord station (a line across the depth, z), moving along y: upper_0 .. upper_n-1 and lower_0 ..
lower_n-1 (the direction +y on both: p > 0 lifts the surface there).
"""
import os
import shutil
import subprocess

import paraview.simple as pvs

import mlsdeform
from mlsdeform.foam import open_case, patch_region
from openfoam_variant import checkmesh  # noqa: F401  (naca0012.checkmesh for the examples)

PATCHES = ['inlet', 'pressure', 'suction', 'frontBack']
QUARTER_CHORD = [0.25, 0.0, 0.5]
FIELD = 'pointSensVecadjS1ESI'   # the adjoint solver adjS1's surface sensitivity, dJ/dx (make-naca0012-case.sh)


def _plane(input, z_low, z_high, diagonal=100.0):
    """A Slip region of the frontBack points with z_low < z < z_high (one of its two planes)."""
    region = pvs.ConstraintRegion(Input=input, Role='Slip', SelectionMode='ImplicitFunction')
    region.Region = 'Box'
    region.Region.UseReferenceBounds = 0
    region.Region.Position = [-diagonal, -diagonal, z_low]
    region.Region.Length = [2 * diagonal, 2 * diagonal, z_high - z_low]
    return region


def deformation(foam_file, distribute=False, **settings):
    """(deformed, dvs): MLS Deform of the case with the design variables aoa and thickness at 0.
    distribute: the case spread over the MPI processes first (RedistributeDataSet; pvbatch
    --symmetric), each deforming its piece."""
    reader = open_case(foam_file, PATCHES, decompose_polyhedra=False)
    if distribute:
        reader = pvs.RedistributeDataSet(Input=reader)
    airfoil = pvs.ExtractBlock(Input=reader, Selectors=['/Root/boundary/pressure', '/Root/boundary/suction'])
    handle = pvs.ConstraintRegion(Input=airfoil, Role='Handle', SelectionMode='AllPoints', UseCentroid=0,
                                  Center=QUARTER_CHORD)
    fixed = patch_region(reader, 'inlet', 'Fixed')
    planes = pvs.ExtractBlock(Input=reader, Selectors=['/Root/boundary/frontBack'])
    front, back = _plane(planes, -0.5, 0.5), _plane(planes, 0.5, 1.5)
    deformed = pvs.MLSDeform(Input=reader, Regions=[handle, fixed, front, back], ExtrusionAxis='Z', **settings)
    dvs = mlsdeform.DesignVariables(deformed)
    dvs.addHandleDV('aoa', handle, rotate=[0, 0, -1], lower=-3, upper=3)
    dvs.addHandleDV('thickness', handle, scale=[0, 1, 0], lower=-0.3, upper=0.3)
    dvs.update()
    return deformed, dvs


def half_thickness(x):
    """The NACA 0012 section's half thickness at chord position x (0 to 1; the open trailing edge)."""
    return 0.6 * (0.2969 * x ** 0.5 - 0.1260 * x - 0.3516 * x ** 2 + 0.2843 * x ** 3 - 0.1015 * x ** 4)


def shape_deformation(foam_file, stations, bound=0.01, **settings):
    """(deformed, dvs): MLS Deform of the case with local shape variables at the chord stations
    (x from 0 to 1) on the upper and lower surfaces, each bounded by +-bound (chords), all at 0."""
    reader = open_case(foam_file, PATCHES, decompose_polyhedra=False)
    surfaces = {}
    for name, patch in (('upper', 'suction'), ('lower', 'pressure')):
        surface = pvs.ExtractBlock(Input=reader, Selectors=['/Root/boundary/' + patch])
        surfaces[name] = pvs.ConstraintRegion(Input=surface, Role='Handle', SelectionMode='AllPoints')
    fixed = patch_region(reader, 'inlet', 'Fixed')
    planes = pvs.ExtractBlock(Input=reader, Selectors=['/Root/boundary/frontBack'])
    front, back = _plane(planes, -0.5, 0.5), _plane(planes, 0.5, 1.5)
    deformed = pvs.MLSDeform(Input=reader, Regions=[surfaces['upper'], surfaces['lower'], fixed, front, back], ExtrusionAxis='Z',
                             **settings)
    dvs = mlsdeform.DesignVariables(deformed)
    for name, side in (('upper', 1.0), ('lower', -1.0)):
        points = [[x, side * half_thickness(x), 0.0] for x in stations]
        dvs.addLocalDV(name, surfaces[name], points=points, direction=[0, 1, 0], axis=[0, 0, 1], lower=-bound, upper=bound)
    dvs.update()
    return deformed, dvs


def source_case(work, primal, adjoint, here=os.path.dirname(os.path.abspath(__file__))):
    """WORK/source/case.foam, made by make-naca0012-case.sh with these iteration counts if it is
    missing (the tutorials fetched into WORK/openfoam-examples)."""
    source = os.path.join(work, 'source')
    if not os.path.exists(os.path.join(source, 'case.foam')):
        subprocess.run(['bash', os.path.join(here, 'make-naca0012-case.sh'), source, str(primal), str(adjoint),
                        os.path.join(work, 'openfoam-examples')], check=True)
    return os.path.join(source, 'case.foam')


def source_deformation(work, primal, adjoint):
    """(source case folder, deformed, dvs) of WORK/source (source_case) with deformation()'s variables."""
    foam_file = source_case(work, primal, adjoint)
    deformed, dvs = deformation(foam_file)
    return os.path.dirname(foam_file), deformed, dvs


def warm_start(case, previous):
    """The case's initial fields are the previous run's final ones (same mesh topology)."""
    latest = max((d for d in os.listdir(previous) if d.replace('.', '', 1).isdigit() and float(d) > 0), key=float)
    initial = os.path.join(case, '0')
    for field in ('U', 'p', 'Ua', 'pa'):
        for ext in ('', '.gz'):
            if os.path.lexists(os.path.join(initial, field + ext)):
                os.unlink(os.path.join(initial, field + ext))
        name = next(field + ext for ext in ('', '.gz') if os.path.exists(os.path.join(previous, latest, field + ext)))
        shutil.copyfile(os.path.join(previous, latest, name), os.path.join(initial, name))


def run_variant(deformed, dvs, values, case, primal, adjoint, previous=None):
    """The design values' variant written to case (unless its mesh fails the quality thresholds)
    and adjointOptimisationFoam run on it, from the previous run's fields when given: a dict with
    quality, ok, and for a variant that passes J and dJ/dp ({variable: value})."""
    dvs.setDesignVars(values)
    dvs.update()
    quality = mlsdeform.meshQuality(dvs)
    result = dict(quality=quality, ok=mlsdeform.passes(quality), case=case)
    if not result['ok']:
        return result
    mlsdeform.foam.save_variant(deformed, os.path.join(case, 'case.foam'), overwrite=True, link=True)
    if previous is not None:
        warm_start(case, previous)
    finish(start_adjoint(case, primal, adjoint), case)
    result['J'] = mlsdeform.readFoamObjective(case)
    result['gradient'] = dvs.totalSensitivity(mlsdeform.readFoamSensitivity(deformed, field=FIELD, case=case))
    return result


def _own(case, name):
    """case/name as the case's own file (a linked variant links the source's: editing through the
    link would edit the source)."""
    path = os.path.join(case, name)
    if os.path.islink(path):
        target = os.path.realpath(path)
        os.unlink(path)
        shutil.copyfile(target, path)
    return path


def foam(command, case):
    """An OpenFOAM command (a string) run in case with Debian's OpenFOAM environment: a Popen."""
    return subprocess.Popen(['bash', '-c', 'source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1; ' + command],
                            cwd=case, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT)


def start_adjoint(case, primal, adjoint, log='log.adjoint'):
    """Starts adjointOptimisationFoam in case with the given iteration counts (adjoint 0: the
    primal and the objective only); returns the Popen. A variant's iteration settings are its own."""
    dictionary, control = _own(case, 'system/optimisationDict'), _own(case, 'system/controlDict')
    adjoint_iterations = max(int(adjoint), 1)  # the objective is written when the adjoint starts
    edits = ['foamDictionary -entry primalSolvers.op1.solutionControls.nIters -set %d %s' % (primal, dictionary),
             'foamDictionary -entry adjointManagers.adjManager1.adjointSolvers.adjS1.solutionControls.nIters -set %d %s'
             % (adjoint_iterations, dictionary),
             'foamDictionary -entry endTime -set %d %s' % (primal + adjoint_iterations, control),
             'foamDictionary -entry writeInterval -set %d %s' % (primal + adjoint_iterations, control)]
    return foam(' > /dev/null && '.join(edits) + ' > /dev/null && adjointOptimisationFoam > %s 2>&1' % log, case)


def finish(process, case, log='log.adjoint'):
    if process.wait() != 0:
        raise RuntimeError('adjointOptimisationFoam failed in %s (see %s)' % (case, os.path.join(case, log)))
