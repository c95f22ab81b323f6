"""Morphing an OpenFOAM case into a variant from pvpython: open the case with ParaView's OpenFOAM
reader, make Constraint Regions of its patches, deform the internal mesh and the patches in one
MLS Deform, and save the variant case (the plugin's OpenFOAM case writer): mlsdeform.foam, once
the plugin is loaded (paraview.simple.LoadPlugin(path, remote=False): its proxies join
paraview.simple)."""
import paraview.simple as pvs

from .deformer import read_faces_ahead


def open_case(foam_file, patches, decompose_polyhedra=True):
    """The case's internal mesh and the named patches, as ParaView's OpenFOAM reader reads them,
    updated; in a builtin session (the reader in this process) a background thread meanwhile reads
    the case's faces for MLS Deform's mesh quality (mlsdeform.deformer.read_faces_ahead)."""
    reader = pvs.OpenFOAMReader(FileName=foam_file)
    reader.MeshRegions = ['internalMesh'] + ['patch/' + p for p in patches]
    reader.Decomposepolyhedra = 1 if decompose_polyhedra else 0
    reader.Cachemesh = 0   # its own second copy of the mesh, kept for time steps a variant does not have (35 MB on 1M cells)
    if reader.GetClientSideObject() is not None:
        read_faces_ahead(foam_file)
    reader.UpdatePipeline()
    return reader


def patch_region(reader, patch, role, **properties):
    """A Constraint Region of the given role holding every point of one patch."""
    block = pvs.ExtractBlock(Input=reader, Selectors=['/Root/boundary/' + patch])
    return pvs.ConstraintRegion(Input=block, Role=role, SelectionMode='AllPoints', **properties)


def layer_region(reader, patch, layers):
    """A Rigid Constraint Region that keeps every cell within `layers` cell layers of a patch rigid
    (its boundary-layer cells, paper section 7.3)."""
    internal = pvs.ExtractBlock(Input=reader, Selectors=['/Root/internalMesh'])
    wall = pvs.ExtractBlock(Input=reader, Selectors=['/Root/boundary/' + patch])
    return pvs.ConstraintRegion(Input=internal, Surface=wall, Role='Rigid', SelectionMode='CellLayers',
                                NumberOfLayers=layers, CellSets=1)


def morph(reader, handle, translation, fixed=(), slip=(), rigid_layers=0, **settings):
    """MLS Deform of the whole case: the handle patches move by translation, fixed patches stay,
    slip patches (planes) slide within their plane; with rigid_layers > 0 the cells within that
    many layers of the handle patches stay rigid. Raises RuntimeError if it failed."""
    regions = [patch_region(reader, p, 'Handle', Translation=list(translation)) for p in handle]
    regions += [patch_region(reader, p, 'Fixed') for p in fixed]
    regions += [patch_region(reader, p, 'Slip') for p in slip]
    if rigid_layers > 0:
        regions += [layer_region(reader, p, rigid_layers) for p in handle]
    deformed = pvs.MLSDeform(Input=reader, Regions=regions, **settings)
    deformed.UpdatePipeline()
    error = deformed.GetDataInformation().GetFieldDataInformation().GetArrayInformation('DeformationError')
    if error is not None:
        raise RuntimeError('MLS Deform failed: %s' % error.GetStringValue(0))
    return deformed


def save_variant(deformed, foam_file, overwrite=False, link=False):
    """Writes the variant case whose .foam file is foam_file (link: its own points only, links to
    the source's unchanged files); raises RuntimeError if nothing was written (the writer's
    message is in the output window)."""
    import os
    pvs.SaveData(foam_file, proxy=deformed, Overwrite=1 if overwrite else 0, LinkUnchangedFiles=1 if link else 0)
    if not os.path.exists(foam_file):
        raise RuntimeError('the variant case %s was not written' % os.path.dirname(foam_file))
