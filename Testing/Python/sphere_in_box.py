"""The MPI tests' scene: a sphere's surface (polydata) inside a tetrahedralized box [-1, 1]^3
(unstructured grid), one block each (named 'sphere' and 'box'), and box-shaped Constraint
Regions on it."""


import math


def write_scene(path, cells, jitter=0.0):
    """The scene as a .vtm file at path; the box has `cells` cells per side (6 tetrahedra each),
    its inner grid points moved by up to `jitter` spacings (a deterministic irregular field: no
    face of the box then has a non-orthogonality or skewness of exactly 0), and the cell set
    'inner' (a cell array)."""
    from vtkmodules.vtkCommonDataModel import vtkImageData, vtkMultiBlockDataSet
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter
    from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
    from vtkmodules.vtkFiltersSources import vtkSphereSource
    from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataWriter
    sphere = vtkSphereSource()
    sphere.SetRadius(0.3)
    sphere.SetThetaResolution(24)
    sphere.SetPhiResolution(16)
    sphere.SetOutputPointsPrecision(1)  # double
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(sphere.GetOutputPort())
    triangles.Update()
    image = vtkImageData()
    image.SetDimensions(cells + 1, cells + 1, cells + 1)
    image.SetOrigin(-1, -1, -1)
    image.SetSpacing(2 / cells, 2 / cells, 2 / cells)
    tets = vtkDataSetTriangleFilter()
    tets.SetInputData(image)
    tets.Update()
    grid = tets.GetOutput()
    for i in range(grid.GetNumberOfPoints()):
        x = grid.GetPoint(i)
        if jitter and max(abs(c) for c in x) < 1 - 1e-9:
            r = [math.sin(12.9898 * x[0] + 78.233 * x[1] + 37.719 * x[2] + 11 * k) for k in range(3)]
            grid.GetPoints().SetPoint(i, *(c + jitter * (2 / cells) * rk for c, rk in zip(x, r)))
    scene = vtkMultiBlockDataSet()
    # a cell set: the cells whose centre lies in [-0.5, 0.5]^3 (1 there, 0 elsewhere)
    from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
    inner = vtkUnsignedCharArray()
    inner.SetName('inner')
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        centre = [sum(grid.GetPoint(ids.GetId(k))[d] for k in range(ids.GetNumberOfIds())) / ids.GetNumberOfIds() for d in range(3)]
        inner.InsertNextValue(1 if max(abs(x) for x in centre) < 0.5 else 0)
    grid.GetCellData().AddArray(inner)
    scene.SetBlock(0, triangles.GetOutput())
    scene.SetBlock(1, grid)
    for block, name in enumerate(('sphere', 'box')):
        scene.GetMetaData(block).Set(vtkMultiBlockDataSet.NAME(), name)
    writer = vtkXMLMultiBlockDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(scene)
    writer.Write()


def box_region(ConstraintRegion, source, role, bounds, **properties):
    """A Constraint Region (the plugin's proxy constructor given) of the points of source in the
    box bounds = [xmin, xmax, ymin, ymax, zmin, zmax]."""
    region = ConstraintRegion(Input=source, Role=role)
    region.Region = 'Box'
    region.Region.UseReferenceBounds = 0
    region.Region.Position = bounds[0::2]
    region.Region.Length = [bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4]]
    for name, value in properties.items():
        setattr(region, name, value)
    return region


def local_scene(ns, source):
    """The sphere is the Handle of 12 local variables along its normals (count=12) and of a pair
    mirrored across x = 0 along +-y (points=) on a Handle in the box; the box's sides are Fixed,
    its floor slips. ns: the script's names, with the plugin's proxy constructors. Returns the
    MLS Deform, its DesignVariables, the two variables' names and the regions."""
    import mlsdeform
    ConstraintRegion, MLSDeform = ns['ConstraintRegion'], ns['MLSDeform']
    body = ConstraintRegion(Input=source, Role='Handle', SelectionMode='Blocks', Blocks=['sphere'])
    fixed = box_region(ConstraintRegion, source, 'Fixed', [-0.99, 0.99, -0.99, 0.99, -1.01, 1.01], InsideOut=1)
    floor = box_region(ConstraintRegion, source, 'Slip', [-0.99, 0.99, -0.99, 0.99, -1.01, -0.99])
    side = box_region(ConstraintRegion, source, 'Handle', [-0.99, 0.99, 0.5, 0.99, -0.99, 0.99])
    deform = MLSDeform(Input=source, Regions=[body, fixed, floor, side], NumberOfSamples=300)
    dvs = mlsdeform.DesignVariables(deform)
    bumps = dvs.addLocalDV('bump', body, count=12, lower=-0.05, upper=0.05)
    pair = dvs.addLocalDV('pair', side, points=[[0.2, 0.6, 0.2]], direction=[0, 1, 0], mirror=([0, 0, 0], [1, 0, 0]),
                          lower=-0.1, upper=0.1)
    return deform, dvs, bumps, pair, (body, fixed, floor, side)


def rest_points(deform):
    """The input points of an MLS Deform proxy, block after block (its output order), as (n, 3)."""
    import numpy as np
    from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet
    data = deform.GetClientSideObject().GetInputDataObject(0, 0)
    blocks = []
    if isinstance(data, vtkCompositeDataSet):
        it = data.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            block = it.GetCurrentDataObject()
            if block.GetNumberOfPoints():
                blocks.append(np.array([block.GetPoint(i) for i in range(block.GetNumberOfPoints())]))
            it.GoToNextItem()
    else:
        blocks.append(np.array([data.GetPoint(i) for i in range(data.GetNumberOfPoints())]))
    return np.concatenate(blocks) if blocks else np.zeros((0, 3))


def reloaded(path, plugin, ns):
    """Saves the ParaView state to path, resets the session, loads the plugin (into the names ns)
    and the state again, and returns the loaded MLS Deform proxy."""
    import paraview.simple as pvs
    pvs.SaveState(path)
    pvs.ResetSession()
    pvs.LoadPlugin(plugin, remote=False, ns=ns)
    pvs.LoadState(path)
    return [p for p in pvs.GetSources().values() if p.GetXMLName() == 'MLSDeform'][0]
