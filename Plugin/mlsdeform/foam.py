"""Morphing an OpenFOAM case into a variant from pvpython: open the case with ParaView's OpenFOAM
reader, make one Constraint Region per role of its patches (by name, pattern or patch group),
deform the internal mesh and the patches in one MLS Deform, and save the variant case (the plugin's OpenFOAM case writer): mlsdeform.foam, once
the plugin is loaded (paraview.simple.LoadPlugin(path, remote=False): its proxies join
paraview.simple)."""
import os

import paraview.simple as pvs
from paraview import servermanager

from .deformer import _load_wrapping, check_foam_file, disjoint_roles, entries, handle_bodies, mesh_regions, read_faces_ahead


def _plugin(name):
    """paraview.simple's constructor of the plugin's proxy name, also when LoadPlugin put the
    constructors into the caller's namespace (ns=globals()) instead of paraview.simple's."""
    if not hasattr(pvs, name):
        pvs._add_functions(vars(pvs))
    if not hasattr(pvs, name):
        raise RuntimeError("mlsdeform.foam makes ParaView proxies: LoadPlugin('.../MLSDeform.so', remote=False) first "
                           "(without ParaView's server manager, use mlsdeform.vtkfoam)")
    return getattr(pvs, name)


def open_case(foam_file, patches, decompose_polyhedra=False):
    """The case's internal mesh and the named patches (names, patterns, patch groups:
    mlsdeform.deformer.mesh_regions), as ParaView's OpenFOAM reader reads them, updated; in a
    builtin session (the reader in this process) a background thread meanwhile reads the case's
    faces for MLS Deform's mesh quality (mlsdeform.deformer.read_faces_ahead). Polyhedra are
    kept as OpenFOAM's cells (decompose_polyhedra False): the mesh quality is then checkMesh's.
    Raises ValueError naming a patch the case does not have, or a file that is no case's."""
    remote = servermanager.ActiveConnection is not None and servermanager.ActiveConnection.IsRemote()
    check_foam_file(foam_file, local=not remote)
    reader = pvs.OpenFOAMReader(FileName=foam_file)
    reader.UpdatePipelineInformation()
    try:
        reader.MeshRegions = mesh_regions(reader.MeshRegions.Available, patches)
    except ValueError as e:
        raise ValueError(f"{foam_file}: {e}") from None
    reader.Decomposepolyhedra = 1 if decompose_polyhedra else 0
    reader.Cachemesh = 0   # its own second copy of the mesh, kept for time steps a variant does not have (35 MB on 1M cells)
    if reader.GetClientSideObject() is not None:
        read_faces_ahead(foam_file)
    reader.UpdatePipeline()
    return reader


def patch_region(reader, patches, role, **properties):
    """A Constraint Region of the given role holding every point of the named patches (names,
    patterns, patch groups: its Blocks); a Handle moves them as one body, a Slip region keeps each
    on its plane."""
    return _plugin('ConstraintRegion')(Input=reader, Role=role, SelectionMode='Blocks', Blocks=entries(patches), **properties)


def layer_region(reader, patch, layers):
    """A Rigid Constraint Region that keeps every cell within `layers` cell layers of a patch rigid
    (its boundary-layer cells, paper section 7.3)."""
    internal = pvs.ExtractBlock(Input=reader, Selectors=['/Root/internalMesh'])
    wall = pvs.ExtractBlock(Input=reader, Selectors=['/Root/boundary/' + patch])
    return _plugin('ConstraintRegion')(Input=internal, Surface=wall, Role='Rigid', SelectionMode='CellLayers',
                                NumberOfLayers=layers, CellSets=1)


def morph(reader, handle, translation, fixed=(), slip=(), rigid_layers=0, **settings):
    """MLS Deform of the whole case: the handle's patches move as one body by translation (handle:
    a patch, pattern or group name, a list of them, or a dict of named bodies {name: patches}, each
    a region of its own), fixed patches stay, slip patches slide within their planes; with
    rigid_layers > 0 the cells within that many layers of the handle patches stay rigid. Its
    Regions hold one region per handle body first, then one Fixed and one Slip region. Raises
    ValueError for a patch in two roles (or two bodies), RuntimeError if it failed."""
    bodies = handle_bodies(handle)
    labelled = [(name, patch_region(reader, patches, 'Handle', Translation=list(translation))) for name, patches in bodies.items()]
    labelled += [(name, patch_region(reader, patches, role)) for name, patches, role in (('fixed', fixed, 'Fixed'), ('slip', slip, 'Slip'))
                 if entries(patches)]
    for _, region in labelled:
        region.UpdatePipeline()
    if all(region.GetClientSideObject() is not None for _, region in labelled):  # (a builtin session)
        disjoint_roles([(name, region.GetClientSideObject()) for name, region in labelled])
    regions = [region for _, region in labelled]
    if rigid_layers > 0:
        regions += [layer_region(reader, p, rigid_layers) for patches in bodies.values() for p in entries(patches)]
    deformed = _plugin('MLSDeform')(Input=reader, Regions=regions, **settings)
    deformed.UpdatePipeline()
    error = deformed.GetDataInformation().GetFieldDataInformation().GetArrayInformation('DeformationError')
    if error is not None:
        raise RuntimeError('MLS Deform failed: %s' % error.GetStringValue(0))
    return deformed


def save_variant(deformed, foam_file, overwrite=False, link=False):
    """Writes the variant case whose .foam file is foam_file (link: its own points only, links to
    the source's unchanged files); raises ValueError for a name that is not a .foam file and
    RuntimeError with the writer's reason if nothing was written."""
    check_foam_file(foam_file, local=False)
    _load_wrapping(readers=True)  # the writer's VTK object as its own class (its LastError)
    writer = pvs.CreateWriter(foam_file, proxy=deformed, Overwrite=1 if overwrite else 0, LinkUnchangedFiles=1 if link else 0)
    writer.UpdatePipeline()
    local = writer.GetClientSideObject()
    reason = local.GetLastError() if local is not None else ''
    if reason or not os.path.exists(foam_file):
        raise RuntimeError(reason or f"the variant case {os.path.dirname(foam_file)} was not written")
