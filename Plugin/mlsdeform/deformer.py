"""An MLS Deform filter as the package drives it: a paraview.simple proxy (pvpython, pvbatch, the
GUI's Python shell) or the VTK object itself (a plain VTK pipeline in python3, mlsdeform.vtkfoam).
``deformer(d)`` gives one interface to both: the VTK algorithm (for the sensitivity methods), its
Constraint Regions with their role, output and design-variable rows, the update, and the variant
written: a deck's (mlsdeform.meshfile) or a case's (mlsdeform.foam's or mlsdeform.vtkfoam's save_variant).
A design-variable row is (name, [kind, axis x, y, z, value, lower, upper]), vtkConstraintRegion's
AddDesignVariable arguments (the proxies' DesignVariables property, 8 entries per row).
"""
import importlib
import os
import sys

_ROW = 8   # name, kind, axis x, y, z, value, lower, upper: one DesignVariables property row
_CONTROL_ROW = 10  # variable, position, direction, line axis: one ControlPoints property row


def check_foam_file(foam_file, local=True):
    """Raises ValueError unless foam_file names a case's .foam file (local: and the case is on
    this machine, with a constant/ folder)."""
    if os.path.splitext(foam_file)[1] not in ('.foam', '.OpenFOAM'):
        raise ValueError(f"{foam_file} is not a .foam file: name the case's .foam file, e.g. "
                         f"{os.path.join(foam_file, 'case.foam')} (an empty file of that name in the case folder)")
    if local and not os.path.isdir(os.path.join(os.path.dirname(os.path.abspath(foam_file)), 'constant')):
        raise ValueError(f"{foam_file}: its folder is not an OpenFOAM case (it has no constant/ folder)")


def _load_wrapping(readers=False):
    """The Python wrapping of the plugin's filters (or of its case writer: readers), built beside
    the plugin as mlsdeform_wrapping: it makes the MLS Deform VTK object's sensitivity methods
    callable. Found on sys.path, beside this package (python3 with the plugin's folder on
    sys.path), or beside the plugin ParaView loaded."""
    module = "mlsdeform_wrapping." + ("MLSDeformReaders" if readers else "MLSDeformFilters")
    try:
        return importlib.import_module(module)
    except ImportError:
        pass
    folders = [os.path.dirname(os.path.dirname(os.path.abspath(__file__)))] if "__file__" in globals() else []
    try:
        from paraview.modules.vtkRemotingCore import vtkPVPluginTracker
        tracker = vtkPVPluginTracker.GetInstance()
        folders += [os.path.dirname(tracker.GetPluginFileName(i)) for i in range(tracker.GetNumberOfPlugins())
                    if tracker.GetPluginName(i) == "MLSDeform" and tracker.GetPluginLoaded(i)]
    except ImportError:
        pass
    for folder in folders:
        if os.path.isdir(os.path.join(folder, "mlsdeform_wrapping")):
            if folder not in sys.path:
                sys.path.append(folder)
            return importlib.import_module(module)
    raise RuntimeError("the MLSDeform plugin's Python wrapping (mlsdeform_wrapping) was not found: LoadPlugin(...) "
                       "the plugin before using mlsdeform in pvpython, or put the plugin's folder on sys.path")


def case_path(data):
    """The OpenFOAM case a dataset was read from: its field data CasePath (a char or string array,
    as VTK's reader writes it), or '' when it has none."""
    path = data.GetFieldData().GetAbstractArray('CasePath') if data is not None else None
    if path is None:
        return ''
    characters = (path.GetValue(i) for i in range(path.GetNumberOfValues()))
    return ''.join(c if isinstance(c, str) else chr(c) for c in characters).split('\0')[0]


def entries(names):
    """A role's names as a list: one name (a str) or several."""
    return [names] if isinstance(names, str) else list(names)


def handle_bodies(handle):
    """The handle's bodies, each moved as one: {name: patches} from one body's patches (a name or
    a list, the body 'handle') or from a dict of named bodies."""
    return dict(handle) if isinstance(handle, dict) else {'handle': entries(handle)}


def disjoint_roles(labelled):
    """Raises ValueError naming the patches that more than one of the regions selected: labelled
    is [(label, vtkConstraintRegion updated in mode Blocks)], e.g. a handle's patch group that takes
    in a slip patch ('wall' holds the ground)."""
    owners = {}
    for label, region in labelled:
        for i in range(region.GetNumberOfSelectedBlocks()):
            owners.setdefault(region.GetSelectedBlockName(i), []).append(label)
    shared = {patch: labels for patch, labels in owners.items() if len(labels) > 1}
    if shared:
        raise ValueError('a patch belongs to one role: ' + '; '.join(f"{patch} is in {' and in '.join(labels)}"
                                                                     for patch, labels in shared.items()))


def mesh_regions(available, names):
    """Of an OpenFOAM reader's mesh regions (available: its 'internalMesh', 'patch/NAME' and
    'group/NAME'), the internal mesh and those that read what names name: patches, patterns of
    whole patch names ('motorBike.*') and patch groups ('motorBikeGroup'), matched as a Constraint
    Region's Blocks match them (vtkConstraintRegion.NamesBlock, NamesGroup). Raises ValueError
    naming the names that name no patch or group, with those of the case."""
    Region = _load_wrapping().vtkConstraintRegion
    names = entries(names)
    chosen, named = ['internalMesh'], set()
    for region in available:
        kind, _, name = region.partition('/')
        hits = [n for n in names if (kind == 'patch' and Region.NamesBlock(n, name)) or (kind == 'group' and Region.NamesGroup(n, name))]
        if hits:
            chosen.append(region)
            named.update(hits)
    missing = [n for n in names if n not in named]
    if missing:
        patches = [r.partition('/')[2] for r in available if r.startswith('patch/')]
        groups = [r.partition('/')[2] for r in available if r.startswith('group/')]
        raise ValueError(f"the case has no patch or patch group {', '.join(missing)} (its patches: {', '.join(patches)}; "
                         f"its groups: {', '.join(groups) or 'none'})")
    return chosen


def read_faces_ahead(foam_file):
    """Starts reading the case's faces, owner and neighbour for MLS Deform's mesh quality in a
    background thread of this process (vtkSubspaceDeformFilter.PrefetchCaseFaces), to run on the
    core VTK's reader leaves idle while it reads the same case: call it right before the reader's
    update. The filter takes them when it measures that case; reading another case drops them."""
    _load_wrapping().vtkSubspaceDeformFilter.PrefetchCaseFaces(os.path.dirname(os.path.abspath(foam_file)))


def _saved_as_mesh_file(algorithm, path, overwrite):
    """Whether the deformation's input came from a mesh file (a deck), whose variant was then
    written to path (a case's variant is written by the caller)."""
    from .meshfile import save_variant, source_of
    if not source_of(algorithm)[0]:
        return False
    save_variant(algorithm, path, overwrite)
    return True


def _checked(algorithm):
    if algorithm.GetClassName() not in ('vtkMLSDeformFilter', 'vtkShellDeformFilter', 'vtkSubspaceDeformFilter'):
        raise RuntimeError(f"design variables go on an MLS Deform filter, not on a {algorithm.GetClassName()} (give "
                           f"DesignVariables the MLS Deform, e.g. the one mlsdeform.foam.morph returns)")
    if not hasattr(algorithm, "ComputeObjectiveSensitivity"):
        raise RuntimeError("the MLS Deform filter's VTK object was handed to Python before mlsdeform was imported, as a "
                           "plain VTK algorithm: import mlsdeform right after LoadPlugin (or before making the filter)")
    return algorithm


def _property_rows(values, width):
    """A repeated property's rows (a name, then width - 1 numbers) as (name, [numbers])."""
    values = list(values)
    return [(str(values[r]), [float(x) for x in values[r + 1:r + width]]) for r in range(0, len(values), width)]


def _getter_rows(count, name, get, width):
    """The same rows from a VTK object's getters: name(i) and get(i, row) for i < count."""
    rows = []
    for i in range(count):
        row = [0.0] * (width - 1)
        get(i, row)
        rows.append((name(i), row))
    return rows


def _add_rows(rows, add):
    """add(name, *numbers) for each (name, numbers) row, the numbers as floats."""
    for name, row in rows:
        add(name, *(float(v) for v in row))


class ProxyDeformer:
    """A paraview.simple MLS Deform proxy; its regions are the proxies of its Regions input."""

    def __init__(self, proxy):
        _load_wrapping()
        algorithm = proxy.GetClientSideObject()
        if algorithm is None:
            raise RuntimeError("mlsdeform needs a builtin session (pvpython or pvbatch without a server connection): "
                               "the sensitivities are computed on the filter itself")
        self.proxy, self.algorithm = proxy, _checked(algorithm)

    def regions(self):
        regions = self.proxy.Regions
        return list(regions) if hasattr(regions, "__len__") else [regions]

    @staticmethod
    def key(region):
        return id(region.SMProxy)

    @staticmethod
    def role(region):
        return region.SMProxy.GetProperty("Role").GetElement(0)

    @staticmethod
    def output(region):
        return region.GetClientSideObject().GetOutputDataObject(0)

    @staticmethod
    def rows(region):
        return _property_rows(region.DesignVariables, _ROW)

    @staticmethod
    def write(region, rows):
        region.DesignVariables = [x for name, row in rows for x in [name, str(int(row[0]))] + [repr(float(v)) for v in row[1:]]]

    @staticmethod
    def controls(region):
        return _property_rows(region.ControlPoints, _CONTROL_ROW)

    @staticmethod
    def write_controls(region, rows):
        region.ControlPoints = [x for name, row in rows for x in [name] + [repr(float(v)) for v in row]]

    @staticmethod
    def region_algorithm(region):
        region.UpdatePipeline()
        return region.GetClientSideObject()

    def update(self):
        self.proxy.UpdatePipeline()

    def save(self, path, overwrite=False, link=False):
        if not _saved_as_mesh_file(self.algorithm, path, overwrite):
            from .foam import save_variant
            save_variant(self.proxy, path, overwrite, link)


class VTKDeformer:
    """A vtkMLSDeformFilter; its regions are the vtkConstraintRegions connected to its port 1."""

    def __init__(self, algorithm):
        _load_wrapping()
        self.algorithm = _checked(algorithm)

    def regions(self):
        return [self.algorithm.GetInputAlgorithm(1, i) for i in range(self.algorithm.GetNumberOfInputConnections(1))]

    @staticmethod
    def key(region):
        return region.__this__

    @staticmethod
    def role(region):
        return region.GetRole()

    @staticmethod
    def output(region):
        return region.GetOutputDataObject(0)

    @staticmethod
    def rows(region):
        return _getter_rows(region.GetNumberOfDesignVariables(), region.GetDesignVariableName, region.GetDesignVariable, _ROW)

    @staticmethod
    def write(region, rows):
        region.RemoveAllDesignVariables()
        _add_rows(rows, lambda name, kind, *row: region.AddDesignVariable(name, int(kind), *row))

    @staticmethod
    def controls(region):
        return _getter_rows(region.GetNumberOfControlPoints(), region.GetControlPointVariable, region.GetControlPoint, _CONTROL_ROW)

    @staticmethod
    def write_controls(region, rows):
        region.RemoveAllControlPoints()
        _add_rows(rows, region.AddControlPoint)

    @staticmethod
    def region_algorithm(region):
        region.Update()
        return region

    def update(self):
        self.algorithm.Update()

    def save(self, path, overwrite=False, link=False):
        if not _saved_as_mesh_file(self.algorithm, path, overwrite):
            from .vtkfoam import save_variant
            save_variant(self.algorithm, path, overwrite, link)


def deformer(d):
    """The interface to an MLS Deform filter given as a paraview.simple proxy or a VTK object."""
    if hasattr(d, "SMProxy"):
        return ProxyDeformer(d)
    if hasattr(d, "GetInputAlgorithm"):
        return VTKDeformer(d)
    raise TypeError(f"an MLS Deform filter (a paraview.simple proxy or a vtkMLSDeformFilter) is needed, not {type(d).__name__}")
