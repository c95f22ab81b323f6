"""Morphing an OpenFOAM case into a variant on a plain VTK pipeline, the twin of mlsdeform.foam
without ParaView's server manager: VTK's OpenFOAM reader, one vtkConstraintRegion per role (its
patches, patterns and patch groups by name), one vtkMLSDeformFilter, the plugin's
vtkOpenFOAMCaseWriter. It runs in Debian's python3 (ParaView's
VTK modules) with the plugin's folder on sys.path, and in pvpython without LoadPlugin; it is what
the design-of-experiments command line (mlsdeform-doe.py) builds, since it holds less memory and
starts faster than paraview.simple (221 MB before a script's first line in pvpython, 312 MB after
``import paraview.simple``).

    reader = open_case('hull/case.foam', ['hull', 'inlet'])
    deform = morph(reader, 'hull', (0.1, 0, 0), fixed=['inlet'])
    save_variant(deform, 'variant/case.foam', link=True)
"""
import os

from .deformer import _load_wrapping, check_foam_file, disjoint_roles, entries, handle_bodies, mesh_regions, read_faces_ahead


def configured_reader(foam_file, patches, decompose_polyhedra=False, fields=()):
    """VTK's OpenFOAM reader of the case's internal mesh, the named patches (names, patterns,
    patch groups: mesh_regions) and the named fields only (point fields as point data, face fields
    as the patches' cell data), with ParaView's Skip Zero Time, no mesh cache (a variant has no
    time steps of its own) and no cell-to-point interpolation, not yet updated. Raises ValueError
    naming a patch the case does not have."""
    from vtkmodules.vtkIOGeometry import vtkOpenFOAMReader
    check_foam_file(foam_file)
    reader = vtkOpenFOAMReader()
    reader.SetFileName(foam_file)
    reader.SetSkipZeroTime(1)
    reader.SetDecomposePolyhedra(1 if decompose_polyhedra else 0)
    reader.SetCacheMesh(0)
    reader.SetCreateCellToPoint(0)
    reader.UpdateInformation()
    available = [reader.GetPatchArrayName(i) for i in range(reader.GetNumberOfPatchArrays())]
    try:
        chosen = mesh_regions(available, patches)
    except ValueError as e:
        raise ValueError(f"{foam_file}: {e}") from None
    for name in available:
        reader.SetPatchArrayStatus(name, 1 if name in chosen else 0)
    for count, get_name, set_status in ((reader.GetNumberOfPointArrays, reader.GetPointArrayName, reader.SetPointArrayStatus),
                                        (reader.GetNumberOfCellArrays, reader.GetCellArrayName, reader.SetCellArrayStatus)):
        for i in range(count()):
            set_status(get_name(i), 1 if get_name(i) in fields else 0)
    return reader


def open_case(foam_file, patches, decompose_polyhedra=False):
    """The case's internal mesh and the named patches (no fields), read by VTK's OpenFOAM reader
    (configured_reader), updated; meanwhile a background thread reads the case's faces for MLS
    Deform's mesh quality (read_faces_ahead). Raises ValueError naming a
    missing patch."""
    reader = configured_reader(foam_file, patches, decompose_polyhedra)
    read_faces_ahead(foam_file)
    reader.Update()
    return reader


def patch_region(reader, patches, role, translation=(0, 0, 0)):
    """A vtkConstraintRegion of the given role (vtkConstraintRegion.Handle, .Fixed, .Slip, ...)
    holding every point of the named patches (names, patterns, patch groups: a Constraint Region's
    Blocks): a Handle moves them as one body by translation, a Slip region keeps each on its plane."""
    Region = _load_wrapping().vtkConstraintRegion
    region = Region()
    region.SetInputConnection(reader.GetOutputPort())
    region.SetRole(role)
    region.SetSelectionMode(Region.Blocks)
    for name in entries(patches):
        region.AddBlock(name)
    if role == Region.Handle:
        region.SetTranslation(*translation)
    return region


def morph(reader, handle, translation, fixed=(), slip=(), **settings):
    """vtkMLSDeformFilter of the whole case, updated: the handle's patches move as one body by
    translation (handle: a patch, pattern or group name, a list of them, or a dict of named bodies
    {name: patches}, each a region of its own), fixed patches stay, slip patches slide within their
    planes; its Regions input (port 1) holds one region per handle body first, then one Fixed and
    one Slip region. settings are MLS Deform properties by name: numbers
    (NumberOfSamples=2000: SetNumberOfSamples(2000)), or an enumeration value by its name in the
    VTK class (Basis='Wendland', ExtrusionAxis='ExtrudedZ'). Raises ValueError for an unknown
    setting or value, or a patch in two roles (or two bodies), and RuntimeError if the deformation
    failed."""
    Region = _load_wrapping().vtkConstraintRegion
    deform = _load_wrapping().vtkMLSDeformFilter()
    for name, value in settings.items():
        setter = getattr(deform, 'Set' + name, None)
        if setter is None:
            raise ValueError(f"MLS Deform has no setting {name} (the VTK filter has no Set{name})")
        if isinstance(value, str):
            named = getattr(deform, value, None)   # an enumeration value by its name in the VTK class
            if not isinstance(named, int) or isinstance(named, bool):
                raise ValueError(f"MLS Deform setting {name}={value!r}: neither a number nor a name of the VTK filter's "
                                 f"enumerations (e.g. Basis 'Wendland', ExtrusionAxis 'ExtrudedZ')")
            value = int(named)
        if isinstance(value, (list, tuple)):
            setter(*value)
        else:
            setter(value)
    deform.SetInputData(0, reader.GetOutput())
    roles = [(name, patches, Region.Handle) for name, patches in handle_bodies(handle).items()]
    roles += [(name, patches, role) for name, patches, role in (('fixed', fixed, Region.Fixed), ('slip', slip, Region.Slip))
              if entries(patches)]
    labelled = []
    for name, patches, role in roles:
        region = patch_region(reader, patches, role, translation)  # held while connected: an output port does not hold its algorithm
        deform.AddInputConnection(1, region.GetOutputPort())
        region.Update()
        labelled.append((name, region))
    disjoint_roles(labelled)
    deform.Update()
    error = deform.GetOutputDataObject(0).GetFieldData().GetAbstractArray('DeformationError')
    if error is not None:
        raise RuntimeError('MLS Deform failed: %s' % error.GetValue(0))
    return deform


def save_variant(deform, foam_file, overwrite=False, link=False):
    """Writes the variant case whose .foam file is foam_file from the deformation's source case
    (link: its own points only, links to the source's unchanged files); raises RuntimeError if
    nothing was written (the writer's message went to VTK's output window, stderr)."""
    writer = _load_wrapping(readers=True).vtkOpenFOAMCaseWriter()
    writer.SetInputConnection(deform.GetOutputPort())
    writer.SetFileName(foam_file)
    writer.SetOverwrite(1 if overwrite else 0)
    writer.SetLinkUnchangedFiles(1 if link else 0)
    writer.Write()
    if writer.GetErrorCode() != 0 or not os.path.exists(foam_file):
        raise RuntimeError(writer.GetLastError() or 'the variant case %s was not written' % os.path.dirname(foam_file))
