"""openfoam_variant's morph on a plain VTK pipeline: Debian's python3 with ParaView's VTK modules and
the plugin's wrapped filters and case writer (mlsdeform_wrapping, beside the plugin), without
ParaView's server manager. The test Python.VTKPipeline and the batch benchmark's first variant
(Testing/Benchmarks/openfoam/vtk_first_variant.py) build their pipeline here."""
import os
import sys


def wrapping(plugin_folder):
    """The wrapped filters and case writer modules from the plugin's folder."""
    if plugin_folder not in sys.path:
        sys.path.insert(0, plugin_folder)
    import mlsdeform_wrapping.MLSDeformFilters as filters
    import mlsdeform_wrapping.MLSDeformReaders as readers
    return filters, readers


def morph(plugin_folder, foam_file, handle, translation, fixed=(), slip=(), decompose_polyhedra=True):
    """The case's internal mesh and patches read by VTK's OpenFOAM reader (no mesh cache), one
    Constraint Region per patch (handle patches moved by translation, fixed ones kept, slip planes
    sliding) and MLS Deform of it all, updated: (reader, deform, regions). Raises RuntimeError when
    the deformation failed."""
    from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet
    from vtkmodules.vtkIOGeometry import vtkOpenFOAMReader
    filters, _ = wrapping(plugin_folder)
    Region = filters.vtkConstraintRegion
    roles = [(p, Region.Handle) for p in handle] + [(p, Region.Fixed) for p in fixed] + [(p, Region.Slip) for p in slip]
    reader = vtkOpenFOAMReader()
    reader.SetFileName(foam_file)
    reader.SetDecomposePolyhedra(1 if decompose_polyhedra else 0)
    reader.SetCacheMesh(0)
    reader.UpdateInformation()
    for i in range(reader.GetNumberOfPatchArrays()):
        name = reader.GetPatchArrayName(i)
        reader.SetPatchArrayStatus(name, 1 if name == 'internalMesh' or name.replace('patch/', '') in dict(roles) else 0)
    reader.Update()
    boundary = reader.GetOutput().GetBlock(1)
    patches = {boundary.GetMetaData(i).Get(vtkMultiBlockDataSet.NAME()): boundary.GetBlock(i) for i in range(boundary.GetNumberOfBlocks())}
    deform = filters.vtkMLSDeformFilter()
    deform.SetInputData(0, reader.GetOutput())
    regions = []
    for name, role in roles:
        region = Region()
        region.SetInputData(patches[name])
        region.SetRole(role)
        region.SetSelectionMode(Region.AllPoints)
        if role == Region.Handle:
            region.SetTranslation(*translation)
        regions.append(region)
        deform.AddInputConnection(1, region.GetOutputPort())
    deform.Update()
    error = deform.GetOutputDataObject(0).GetFieldData().GetAbstractArray('DeformationError')
    if error is not None:
        raise RuntimeError('MLS Deform failed: %s' % error.GetValue(0))
    return reader, deform, regions


def save_variant(plugin_folder, deform, foam_file, link=True):
    """Writes the variant case whose .foam file is foam_file (link: its own points only); returns
    the writer (its error code tells whether it failed; nothing is written then)."""
    _, readers = wrapping(plugin_folder)
    writer = readers.vtkOpenFOAMCaseWriter()
    writer.SetInputConnection(deform.GetOutputPort())
    writer.SetFileName(foam_file)
    writer.SetLinkUnchangedFiles(1 if link else 0)
    writer.Write()
    return writer
