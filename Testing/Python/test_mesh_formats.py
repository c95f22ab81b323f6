"""Issue 56: every solver's mesh goes back to its solver. For each format, a mesh made by a
third-party tool (Gmsh, ...) is opened in pvpython with the Mesh File reader, deformed with a
region picked by one of its named sets, saved with Save Data as a variant in its own format, and
the variant read back by an independent tool (meshio, Gmsh, ...): its points the deformed ones to
the format's precision, every other byte or record the source's.

  pvpython test_mesh_formats.py PLUGIN WORK
"""
import os
import shutil
import subprocess
import sys

import numpy as np
from paraview import servermanager as sm
from paraview.simple import LoadPlugin, OpenDataFile, SaveData
from vtkmodules.util.numpy_support import vtk_to_numpy

from checks import check, finish

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


def morph(path, handle, fixed):
    """The mesh file opened, the handle set moved by (0.1, 0.05, 0), the fixed sets kept: (reader,
    deformation, NodeIds, moved points)."""
    reader = OpenDataFile(path)
    check(reader.GetXMLName() == 'MeshFileReader', '%s opens with the Mesh File reader' % os.path.basename(path))
    still = ConstraintRegion(Input=reader, Role='Fixed', SelectionMode='Blocks', Sets=fixed)  # noqa: F821 (the plugin's)
    moving = ConstraintRegion(Input=reader, Role='Handle', SelectionMode='Blocks', Sets=[handle], Translation=[0.1, 0.05, 0])  # noqa: F821
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
finish()
