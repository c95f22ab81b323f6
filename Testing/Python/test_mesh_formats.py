"""Issue 56: every solver's mesh goes back to its solver. For each format, a mesh made by a
third-party tool (Gmsh, ...) is opened in pvpython with the Mesh File reader, deformed with a
region picked by one of its named sets, saved with Save Data as a variant in its own format, and
the variant read back by an independent tool (meshio, Gmsh, ...): its points the deformed ones to
the format's precision, every other byte or record the source's.

  pvpython test_mesh_formats.py PLUGIN WORK
"""
import os
import re
import shutil
import subprocess
import sys

import numpy as np
from paraview import servermanager as sm
from paraview.simple import LoadPlugin, OpenDataFile, SaveData
from vtkmodules.util.numpy_support import vtk_to_numpy

from checks import check, finish
from foam_box import FOAM, box_case

plugin, work = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

# A box with a spherical hole, its faces as physical groups: the sphere is the handle.
GEO = '''SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 4, 2, 2};
Sphere(2) = {2, 1, 1, 0.5};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
e = 1e-6;
Physical Volume("fluid") = {3};
Physical Surface("inlet") = Surface In BoundingBox{-e, -e, -e, e, 2 + e, 2 + e};
Physical Surface("outlet") = Surface In BoundingBox{4 - e, -e, -e, 4 + e, 2 + e, 2 + e};
Physical Surface("body") = Surface In BoundingBox{1.5 - e, 0.5 - e, 0.5 - e, 2.5 + e, 1.5 + e, 1.5 + e};
Mesh.CharacteristicLengthMax = 0.35;
'''
geo = os.path.join(work, 'box.geo')
with open(geo, 'w') as f:
    f.write(GEO)


def python3(code, *args):
    """Debian's python3 (meshio) on code; its stdout."""
    return subprocess.run(['/usr/bin/python3', '-c', code] + list(args), capture_output=True, text=True, check=True).stdout


def doe(deform, folder, extension, fem):
    """A design of experiments of 2 variants on the deformation's handle: variant files of the
    source's format, each with the verdict of its solver family (FEM or checkMesh's), written
    whatever the verdict."""
    import mlsdeform
    dvs = mlsdeform.DesignVariables(deform)
    dvs.addHandleDV('dx', [deform.Regions[1]], translate=[1, 0, 0], lower=-0.1, upper=0.1)
    rows = mlsdeform.designOfExperiments(dvs, folder, samples=2, verbose=False, writeFailed=True)  # (Gmsh's tetrahedra here
    # have scaled Jacobians below the FEM threshold already: written all the same, with their verdict)
    figure = 'MinScaledJacobian' if fem else 'MaxNonOrthogonality'
    check(len(rows) == 2 and all(figure in r and r['path'].endswith(extension) and os.path.exists(r['path']) for r in rows),
          'a design of experiments writes %s variants with the %s verdict (%s)' % (extension, 'FEM' if fem else 'checkMesh',
                                                                                  [r.get(figure) for r in rows]))


def foam_points(path):
    """The points of an ASCII OpenFOAM points file."""
    lines = open(path).read().splitlines()
    start = next(i for i, line in enumerate(lines) if line.strip().isdigit() and lines[i + 1].strip() == '(')
    count = int(lines[start])
    return np.array([line.strip('()').split() for line in lines[start + 2:start + 2 + count]], dtype=float)


def morph(path, handle, fixed, reader=None):
    """The mesh file opened (by File > Open's choice, or the reader given), the handle set moved by
    (0.1, 0.05, 0), the fixed sets kept: (reader, deformation, NodeIds, moved points). handle None:
    the points within 0.6 of the box's centre move, fixed None: those within 0.2 of its ends stay."""
    reader = reader or OpenDataFile(path)
    check(reader.GetXMLName() == 'MeshFileReader', '%s opens with the Mesh File reader' % os.path.basename(path))
    if fixed:
        still = ConstraintRegion(Input=reader, Role='Fixed', SelectionMode='Blocks', Sets=fixed)  # noqa: F821 (the plugin's)
    else:
        still = ConstraintRegion(Input=reader, Role='Fixed', InsideOut=1)  # noqa: F821
        still.Region = 'Box'
        still.Region.Position, still.Region.Length = [0.2, -1, -1], [3.6, 4, 4]
    if handle:
        moving = ConstraintRegion(Input=reader, Role='Handle', SelectionMode='Blocks', Sets=[handle], Translation=[0.1, 0.05, 0])  # noqa: F821
    else:
        moving = ConstraintRegion(Input=reader, Role='Handle', Translation=[0.1, 0.05, 0])  # noqa: F821
        moving.Region = 'Sphere'
        moving.Region.Center, moving.Region.Radius = [2, 1, 1], 0.6
    deform = MLSDeform(Input=reader, Regions=[still, moving])  # noqa: F821
    out = sm.Fetch(deform)
    ids = vtk_to_numpy(out.GetPointData().GetArray('NodeId'))
    return reader, deform, ids, vtk_to_numpy(out.GetPoints().GetData()).astype(float)


# SU2 (Gmsh's writer; markers), read back by meshio.
source = os.path.join(work, 'su2', 'box.su2')
os.makedirs(os.path.dirname(source))
subprocess.run(['gmsh', '-3', geo, '-format', 'su2', '-o', source], check=True, stdout=subprocess.DEVNULL)
reader, deform, ids, moved = morph(source, 'body', ['inlet', 'outlet'])
variant = os.path.join(work, 'su2', 'variant', 'box.su2')
SaveData(variant, proxy=deform)
points = np.array([float(v) for v in python3('import meshio, sys; m = meshio.read(sys.argv[1]); print(*m.points.ravel())', variant).split()])
points = points.reshape(-1, 3)
check(len(points) == len(moved) and np.array_equal(points[ids], moved),
      'SU2: meshio reads the variant with the deformed points exactly (%d points)' % len(moved))
body = open(source).read().split('NMARK', 1)[1]
check(open(variant).read().split('NMARK', 1)[1] == body, 'SU2: the markers are the source\'s, byte for byte')
doe(deform, os.path.join(work, 'su2', 'doe'), '.su2', fem=False)

# Nastran bulk data (Gmsh's writer, small and free field: grids, CTETRA, CTRIA3), read back by Gmsh
# (meshio 5 wants a BEGIN BULK that Gmsh does not write): the points to the field's precision
# (small field: 8 characters, 1e-6 of the box's size; free field: the shortest exact text, which
# Gmsh's .msh keeps to 16 digits), every other card the source's.
grid = re.compile(r'^GRID.*$(\n[+*].*$)?', re.M)
for field, tolerance in ((1, 1e-6), (0, 1e-15)):  # Gmsh writes 16 significant digits
    name = ('small', 'free')[field == 0]
    source = os.path.join(work, 'nastran-' + name, 'box.bdf')
    os.makedirs(os.path.dirname(source))
    subprocess.run(['gmsh', '-3', geo, '-format', 'bdf', '-setnumber', 'Mesh.BdfFieldFormat', str(field), '-o', source],
                   check=True, stdout=subprocess.DEVNULL)
    reader, deform, ids, moved = morph(source, None, None)
    variant = os.path.join(work, 'nastran-' + name, 'variant', 'box.bdf')
    SaveData(variant, proxy=deform)
    reread = os.path.join(work, 'nastran-' + name, 'reread.msh')
    run = subprocess.run(['gmsh', variant, '-0', '-o', reread], capture_output=True, text=True)
    back = sm.Fetch(OpenDataFile(reread))  # Gmsh's reading of the variant, in its own format
    gmsh_points = dict(zip(vtk_to_numpy(back.GetPointData().GetArray('NodeId')).tolist(), vtk_to_numpy(back.GetPoints().GetData())))
    gap = max(np.abs(gmsh_points[n] - p).max() for n, p in zip(ids.tolist(), moved))
    check(run.returncode == 0 and gap <= tolerance * 4, 'Nastran %s field: Gmsh reads the variant at the deformed points '
          '(largest gap %.2g)' % (name, gap))
    check(grid.sub('', open(variant).read()) == grid.sub('', open(source).read()), 'Nastran: every card but the grids is the source\'s')
    if field == 0:
        doe(deform, os.path.join(work, 'nastran-free', 'doe'), '.bdf', fem=True)

# Exodus II (ParaView's own writer, a tetrahedral box) and CGNS (ParaView's own writer, CGNS 4),
# opened with ParaView's own readers (IOSS and Exodus II; CGNS), which record neither the file nor
# (CGNS) node ids: the variant writer finds the file up the pipeline and the nodes by the readers'
# node ids (Exodus) or zones (CGNS). Saved with the variant writer named (Save Data picks it too:
# test_save_data_default.py), read back by ParaView's readers: the points
# the deformed ones, to float precision where ParaView wrote single precision coordinates.
from paraview.simple import CGNSSeriesReader, ExodusIIReader, ExodusIIWriter, IOSSReader, MergeBlocks, Tetrahedralize, Wavelet  # noqa: E402
box = Tetrahedralize(Input=Wavelet(WholeExtent=[0, 8, 0, 4, 0, 4]))
exodus = os.path.join(work, 'exodus', 'box.exo')
cgns = os.path.join(work, 'cgns', 'box.cgns')
os.makedirs(os.path.dirname(exodus))
os.makedirs(os.path.dirname(cgns))
ExodusIIWriter(FileName=exodus, Input=box).UpdatePipeline()
SaveData(cgns, proxy=box)


def merged_points(proxy, ids_name):
    """The points of a reader's or filter's output, merged, in the order of their node ids."""
    block = sm.Fetch(MergeBlocks(Input=proxy))
    points = vtk_to_numpy(block.GetPoints().GetData()).astype(float)
    if ids_name is None:  # CGNS: one zone, in file order
        return points
    return points[np.argsort(vtk_to_numpy(block.GetPointData().GetArray(ids_name)))]


for source, opener, ids_name, tolerance in ((exodus, IOSSReader, 'ids', 6e-8), (exodus, ExodusIIReader, 'GlobalNodeId', 6e-8),
                                            (cgns, CGNSSeriesReader, None, 0)):
    name = opener.__name__
    reader = OpenDataFile(source) if opener is not ExodusIIReader else ExodusIIReader(FileName=source)
    check(reader.GetXMLName() == name, '%s opens with ParaView\'s %s' % (os.path.basename(source), name))
    still = ConstraintRegion(Input=reader, Role='Fixed', InsideOut=1)  # noqa: F821 (the plugin's)
    still.Region = 'Box'
    still.Region.Position, still.Region.Length = [0.2, -1, -1], [7.6, 6, 6]
    moving = ConstraintRegion(Input=reader, Role='Handle', Translation=[0.1, 0.05, 0])  # noqa: F821
    moving.Region = 'Sphere'
    moving.Region.Center, moving.Region.Radius = [4, 2, 2], 1.5
    deform = MLSDeform(Input=[reader], Regions=[still, moving])  # noqa: F821
    moved = merged_points(deform, ids_name)
    variant = os.path.join(work, name, os.path.basename(source))
    offered = sm.vtkSMProxyManager.GetProxyManager().GetWriterFactory().GetSupportedFileTypes(deform.SMProxy, 0)
    check(offered.startswith('A variant of the source mesh file'),
          "Save Data offers the variant writer first for a deformation of what ParaView's %s read" % name)
    writer = sm.writers.MeshFileVariant(Input=deform, FileName=variant)
    writer.UpdatePipeline()
    back = merged_points(opener(FileName=variant) if opener is not CGNSSeriesReader else CGNSSeriesReader(FileNames=[variant]), ids_name)
    gap = np.abs(back - moved).max()
    check(len(back) == len(moved) and np.abs(moved - merged_points(reader, ids_name)).max() > 0.01 and
          gap <= tolerance * np.abs(moved).max(), '%s: a deformation of what ParaView\'s %s read is written as a variant and read '
          'back at the deformed points (%d points, largest gap %.2g)' % (os.path.splitext(source)[1], name, len(moved), gap))
    if opener is IOSSReader:
        # a dataset of another mesh (the box with one point less) is refused, nothing written
        other = os.path.join(work, name, 'other.exo')
        bad = sm.writers.MeshFileVariant(Input=Tetrahedralize(Input=Wavelet(WholeExtent=[0, 8, 0, 4, 0, 3])), FileName=other,
                                         SourceFile=source)
        bad.UpdatePipeline()
        check(not os.path.exists(other), 'a dataset without node ids of the source is refused: nothing written')
        doe(deform, os.path.join(work, 'exodus', 'doe'), '.exo', fem=True)  # Exodus: a structural solver's mesh
    if opener is CGNSSeriesReader:
        doe(deform, os.path.join(work, 'cgns', 'doe'), '.cgns', fem=False)

# Fluent (OpenFOAM's foamMeshToFluent on a blockMesh box; zones), converted back by
# fluentMeshToFoam and checked by checkMesh: the points are the deformed ones (OpenFOAM's own
# parsing of a number may differ from the nearest double by 1 ulp).
if os.path.exists('/usr/share/openfoam/etc/bashrc'):
    case = os.path.join(work, 'fluent', 'box')
    box_case(case)
    subprocess.run(['bash', '-c', FOAM + 'cd "%s" && foamMeshToFluent > log.foamMeshToFluent' % case], check=True)
    source = os.path.join(case, 'fluentInterface', 'box.msh')
    reader, deform, ids, moved = morph(source, 'lid', ['base'])
    variant = os.path.join(work, 'fluent', 'variant', 'box.msh')
    SaveData(variant, proxy=deform)
    back = os.path.join(work, 'fluent', 'back')
    shutil.copytree(os.path.join(case, 'system'), os.path.join(back, 'system'))
    log = subprocess.run(['bash', '-c', FOAM + 'cd "%s" && fluentMeshToFoam "%s" > log.fluentMeshToFoam && checkMesh' % (back, variant)],
                         capture_output=True, text=True)
    check('Mesh OK.' in log.stdout, 'Fluent: fluentMeshToFoam converts the variant and checkMesh passes')
    points = foam_points(os.path.join(back, 'constant', 'polyMesh', 'points'))
    check(len(points) == len(moved) and np.allclose(points[ids - 1], moved, rtol=1e-15, atol=1e-15 * np.abs(moved).max()),
          'Fluent: the converted points are the deformed ones (%d points)' % len(moved))
    coordinates = re.compile(r'^[ \t]*[-+0-9.eE]+[ \t]+[-+0-9.eE]+[ \t]+[-+0-9.eE]+[ \t]*$', re.M)  # a node's line
    check(coordinates.sub('', open(variant).read()) == coordinates.sub('', open(source).read()),
          'Fluent: every line but the nodes\' is the source\'s, byte for byte')
else:
    check(False, 'OpenFOAM (foamMeshToFluent) is installed for the Fluent round trip (Debian package openfoam)')
finish()
