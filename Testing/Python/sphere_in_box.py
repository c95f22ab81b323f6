"""The MPI tests' scene: a sphere's surface (polydata) inside a tetrahedralized box [-1, 1]^3
(unstructured grid), one block each, and box-shaped Constraint Regions on it."""


def write_scene(path, cells):
    """The scene as a .vtm file at path; the box has `cells` cells per side (6 tetrahedra each)."""
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
    scene = vtkMultiBlockDataSet()
    scene.SetBlock(0, triangles.GetOutput())
    scene.SetBlock(1, tets.GetOutput())
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
