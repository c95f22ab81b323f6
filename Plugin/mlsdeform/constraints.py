"""Geometric constraint functions of a design with exact gradients, in the form of pyGeo's
DVConstraints: thickness "toothpicks", the volume a closed surface encloses, a surface's area,
linear relations between variables and the mesh's quality (KS-aggregated), each chained to the
design variables through the deformation's reverse mode (``DesignVariables.totalSensitivity``).

    cons = mlsdeform.DesignConstraints(dvs)
    cons.addThicknessConstraints2D('thick', le, te, nSpan=1, nChord=10, surface='aerofoil', lower=1.0)
    cons.addTriangulatedVolumeConstraint('volume', surface='aerofoil', axis=[0, 0, 1], lower=1.0)
    cons.addLeTeConstraints('le', ['upper_0'], ['lower_0'])
    cons.addMeshQualityConstraint('nonOrtho', 'nonOrthogonality', upper=70)
    funcs, sens = {}, {}
    cons.evalFunctions(funcs); cons.evalFunctionsSens(sens)
    scipy.optimize.minimize(..., constraints=cons.getScipyConstraints(), method='SLSQP')

Surfaces are the output's polygons (the 2D cells of its blocks: an OpenFOAM case's patches) of
the blocks named (a name, a pattern or a list, as a Constraint Region's Blocks match
them; None: every block with polygons), each polygon a fan of triangles from its first point: the
triangles' corners are output points, so a point of the surface (a toothpick's end) is carried by
the deformation with its barycentric coordinates. Under MPI (pvbatch --symmetric) each process
measures its piece, the values are summed (every process gets the same) and a gradient at a
position several processes hold is summed over them before it is chained.
"""
import math

import numpy as np

from .deformer import _load_wrapping
from .ranks import all_gather, all_reduce, controller, rank

_UNBOUNDED = 1e300


def _finite_bound(value, what):
    if value is None:
        return None
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{what} must be a finite number or None, not {value!r}")
    return value


def _points(value, what, count=None):
    a = np.asarray(value, dtype=float)
    if a.ndim != 2 or a.shape[1] != 3 or (count is not None and len(a) != count) or len(a) == 0:
        raise ValueError(f"{what} must be an (n, 3) array of points{'' if count is None else f' with n = {count}'}, "
                         f"not shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{what} has values that are not finite")
    return a


class _Surface:
    """The triangles of the output's polygons on the named blocks: corner indices into this
    process's output points (T x 3) and the blocks' names."""

    def __init__(self, output, names, what):
        from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet
        Region = _load_wrapping().vtkConstraintRegion
        wanted = None if names is None else ([names] if isinstance(names, str) else list(names))
        leaves = []
        if isinstance(output, vtkCompositeDataSet):
            it = output.NewIterator()
            it.InitTraversal()
            while not it.IsDoneWithTraversal():
                meta = it.GetCurrentMetaData() if it.HasCurrentMetaData() else None
                name = meta.Get(vtkCompositeDataSet.NAME()) if meta is not None and meta.Has(vtkCompositeDataSet.NAME()) else ''
                leaves.append((name or '', it.GetCurrentDataObject()))
                it.GoToNextItem()
        else:
            leaves.append(('', output))
        triangles, offset, found, named = [], 0, [], set()
        for name, block in leaves:
            hits = [] if wanted is None else [n for n in wanted if Region.NamesBlock(n, name)]
            polygons = _polygons(block) if wanted is None or hits else None
            if polygons is not None:
                offsets, connectivity = polygons
                sizes = np.diff(offsets)
                for n in np.unique(sizes):
                    starts = offsets[:-1][sizes == n]
                    for k in range(1, n - 1):  # the fan (p0, pk, pk+1)
                        triangles.append(np.stack([connectivity[starts], connectivity[starts + k], connectivity[starts + k + 1]],
                                                  axis=1) + offset)
                found.append(name)
                named.update(hits)
            offset += block.GetNumberOfPoints() if block is not None else 0
        self.triangles = np.concatenate(triangles) if triangles else np.zeros((0, 3), dtype=np.int64)
        self.blocks = found
        missing = [] if wanted is None else [n for n in wanted if not all_reduce(int(n in named), 'max')]
        if missing or all_reduce(len(self.triangles), 'sum') == 0:
            which = 'the output' if wanted is None else ', '.join(map(repr, missing or wanted))
            raise ValueError(f"{what}: {which} names no block with surface polygons (2D cells, such as an "
                             f"OpenFOAM case's patches); blocks with polygons here: {', '.join(found) or 'none'}")

    def polygons(self):
        """The triangles as a vtkIdTypeArray (a tuple of 3 corners each) for the filter's surface
        measures (ComputeSurfaceVolume, ComputeSurfaceArea), made once: the filter keeps what it
        found on it for this array."""
        if not hasattr(self, '_polygons'):
            from vtkmodules.util.numpy_support import vtk_to_numpy
            from vtkmodules.vtkCommonCore import vtkIdTypeArray
            self._polygons = vtkIdTypeArray()
            self._polygons.SetNumberOfComponents(3)
            self._polygons.SetNumberOfTuples(len(self.triangles))
            vtk_to_numpy(self._polygons).reshape(-1, 3)[:] = self.triangles
        return self._polygons

    def corners(self, X):
        """The triangles' corners x0, x1, x2 on the points X, once per X (the same array: the
        lines of thickness constraints cast on a design's points)."""
        if getattr(self, '_on', None) is not X:
            self._on, self._corners = X, (X[self.triangles[:, 0]], X[self.triangles[:, 1]], X[self.triangles[:, 2]])
        return self._corners


def _polygons(block):
    """The polygons of a block (a polydata's polys; an unstructured grid's triangles, quads and
    polygons, as a redistributed polydata becomes), less another process's held as ghosts (VTK's
    DUPLICATECELL: counted there): (offsets, connectivity), or None."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import (vtkDataSetAttributes, vtkPolyData, vtkUnstructuredGrid, VTK_POLYGON, VTK_QUAD,
                                               VTK_TRIANGLE)
    if isinstance(block, vtkPolyData):
        cells, keep = block.GetPolys(), None
        first = block.GetNumberOfVerts() + block.GetNumberOfLines()  # the polys' first cell id
    elif isinstance(block, vtkUnstructuredGrid) and block.GetNumberOfCells() > 0:
        cells, first = block.GetCells(), 0
        keep = np.isin(vtk_to_numpy(block.GetCellTypesArray()), [VTK_TRIANGLE, VTK_QUAD, VTK_POLYGON])
    else:
        return None
    if cells.GetNumberOfCells() == 0:
        return None
    ghosts = block.GetCellGhostArray()
    if ghosts is not None:
        own = (vtk_to_numpy(ghosts)[first:first + cells.GetNumberOfCells()] & vtkDataSetAttributes.DUPLICATECELL) == 0
        keep = own if keep is None else keep & own
    offsets = vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64)
    connectivity = vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64)
    if keep is not None:
        if not keep.any():
            return None
        starts, sizes = offsets[:-1][keep], np.diff(offsets)[keep]
        connectivity = np.concatenate([connectivity[a:a + n] for a, n in zip(starts, sizes)])
        offsets = np.concatenate([[0], np.cumsum(sizes)])
    sizes = np.diff(offsets)
    if not np.any(sizes >= 3):
        return None
    return offsets, connectivity


def _position_ids(P):
    """A number per row of P (n, 3), equal for equal positions (-0 and 0 alike): by one lexsort."""
    P = np.asarray(P, dtype=float) + 0.0
    order = np.lexsort((P[:, 2], P[:, 1], P[:, 0]))
    ordered = P[order]
    new = np.ones(len(P), dtype=bool)
    new[1:] = np.any(ordered[1:] != ordered[:-1], axis=1)
    ids = np.empty(len(P), dtype=np.int64)
    ids[order] = np.cumsum(new) - 1
    return ids


class _Constraint:
    """One constraint function (an array of m values): bounds, scaling, how to evaluate it."""

    def __init__(self, name, kind, lower, upper, scaled, evaluate, linear=None):
        self.name, self.kind, self.scaled = name, kind, scaled
        self.lower, self.upper = lower, upper
        self.evaluate = evaluate   # X -> (values (m,), [dC_i/dX as (points, values)] or None for values alone)
        self.linear = linear       # for a linear constraint: its matrix over the variables (m x ndv)
        self.baseline = None


class DesignConstraints:
    """Constraint functions of the design variables ``dvs`` (a DesignVariables), pyGeo's
    DVConstraints' methods where the meaning is the same. Each function's values are arrays
    (one entry per thickness, one for a volume); ``scaled=True`` (the default, as pyGeo) divides
    them by their baseline values (those when the constraint is added) so that the bounds are
    relative (lower=1.0: at least the baseline), ``scaled=False`` keeps absolute values.
    Raises ValueError and adds nothing for bad input."""

    def __init__(self, dvs):
        self.dvs = dvs
        self._constraints = {}
        self._cache = None   # (values of the variables, X)
        self._surfaces = {}  # the surfaces the constraints measure, by their blocks' names

    # -- the functions ------------------------------------------------------------------------
    def addThicknessConstraints1D(self, name, ptList, nCon, axis, surface=None, lower=1.0, upper=3.0, scaled=True):
        """nCon thicknesses along the polyline ptList (points evenly spaced along it, ends
        included): at each point the line along ``axis`` is cast both ways to the nearest surface
        polygon, and the distance between the two hits (carried by the deformation) is the
        thickness. Raises ValueError for a line that misses the surface on a side."""
        pts = _points(ptList, f"thickness constraints {name!r}: ptList")
        if len(pts) < 2 or isinstance(nCon, bool) or not isinstance(nCon, (int, np.integer)) or nCon < 1:
            raise ValueError(f"thickness constraints {name!r}: ptList needs 2 or more points and nCon a whole number >= 1")
        lengths = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
        s = np.linspace(0, lengths[-1], nCon)
        at = np.stack([np.interp(s, lengths, pts[:, c]) for c in range(3)], axis=1)
        self._thickness(name, at, np.tile(self._direction(axis, name), (nCon, 1)), surface, lower, upper, scaled)

    def addThicknessConstraints2D(self, name, leList, teList, nSpan, nChord, surface=None, lower=1.0, upper=3.0, scaled=True):
        """nSpan x nChord thicknesses on the grid between the leading-edge line leList and the
        trailing-edge line teList (each 2 or more points; nSpan stations along them, nChord
        between them, ends included; nSpan = 1: the lines' middle, as a 2D case's mid-depth),
        each cast along the normal of the grid's plane (the span's direction times the chord's)
        to the surface both ways. Values in span-major order (pyGeo's)."""
        le = _points(leList, f"thickness constraints {name!r}: leList")
        te = _points(teList, f"thickness constraints {name!r}: teList", len(le))
        for n, what in ((nSpan, 'nSpan'), (nChord, 'nChord')):
            if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
                raise ValueError(f"thickness constraints {name!r}: {what} must be a whole number >= 1, not {n!r}")
        if len(le) < 2:
            raise ValueError(f"thickness constraints {name!r}: leList and teList need 2 or more points each")
        span = np.linspace(0, 1, nSpan) if nSpan > 1 else np.array([0.5])
        u = np.linspace(0, 1, len(le))
        at, directions = [], []
        for t in span:
            a = np.array([np.interp(t, u, le[:, c]) for c in range(3)])
            b = np.array([np.interp(t, u, te[:, c]) for c in range(3)])
            spanwise = le[-1] - le[0]
            normal = np.cross(spanwise, b - a)
            if np.linalg.norm(normal) <= 1e-12 * np.linalg.norm(spanwise) * np.linalg.norm(b - a):
                raise ValueError(f"thickness constraints {name!r}: the leading and trailing edges span no plane "
                                 "(the chord is along the span, or a line has no length)")
            for c in np.linspace(0, 1, nChord):
                at.append(a + c * (b - a))
                directions.append(normal / np.linalg.norm(normal))
        self._thickness(name, np.array(at), np.array(directions), surface, lower, upper, scaled)

    def addTriangulatedVolumeConstraint(self, name, surface=None, axis=None, lower=1.0, upper=3.0, scaled=True):
        """The volume the closed surface of the named blocks encloses, by the divergence theorem
        over its triangles: V = 1/3 sum c_t . S_t (c_t, S_t a triangle's centroid and area
        vector), exact for the triangulated surface. With ``axis`` (an extruded shape: a one-cell
        thick 2D case, whose surface is open at its front and back) the in-plane field x - (x.a)a,
        whose flux through the front and back is zero: V = 1/2 sum P c_t . S_t (P = I - a a^T),
        the cross-section's area times the depth. Raises ValueError for an open surface (an edge
        of one triangle only, other than on the front and back with an axis)."""
        what = f"volume constraint {name!r}"
        self._check_name(name)
        surf = self._surface(surface, what)
        a = None if axis is None else self._direction(axis, name)
        X = self._points()
        self._check_closed(surf, X, a, what)
        algorithm, axis = self.dvs._algorithm, [0.0, 0.0, 0.0] if a is None else list(a)
        sign = None

        def evaluate(X, gradient=True):
            nonlocal sign
            value, g = self._computed(lambda v, r, d: algorithm.ComputeSurfaceVolume(surf.polygons(), axis, v, r, d), gradient)
            V = value.GetValue(0)
            if sign is None:
                sign = 1.0 if V >= 0 else -1.0   # the surface's orientation (a case's patches point into the body)
            return np.array([sign * V]), None if g is None else [(g[0], sign * g[1])]

        self._add(_Constraint(name, 'volume', lower, upper, scaled, evaluate))

    def addSurfaceAreaConstraint(self, name, surface=None, lower=1.0, upper=3.0, scaled=True):
        """The area of the named blocks' polygons (their triangles' sum)."""
        self._check_name(name)
        surf = self._surface(surface, f"area constraint {name!r}")
        algorithm = self.dvs._algorithm

        def evaluate(X, gradient=True):
            value, g = self._computed(lambda v, r, d: algorithm.ComputeSurfaceArea(surf.polygons(), v, r, d), gradient)
            return np.array([value.GetValue(0)]), None if g is None else [g]

        self._add(_Constraint(name, 'area', lower, upper, scaled, evaluate))

    def addLinearConstraintsShape(self, name, indSetA, indSetB, factorA, factorB, lower=0.0, upper=0.0):
        """factorA p[indSetA[i]] + factorB p[indSetB[i]] between lower and upper, for each i (the
        variables by name, or by their index in getVarNames())."""
        self._check_name(name)
        names = self.dvs.getVarNames()

        def column(v):
            if isinstance(v, str):
                if v not in names:
                    raise ValueError(f"linear constraints {name!r}: unknown design variable {v!r}")
                return names.index(v)
            if isinstance(v, (int, np.integer)) and not isinstance(v, bool) and 0 <= v < len(names):
                return int(v)
            raise ValueError(f"linear constraints {name!r}: {v!r} is neither a design variable's name nor its index")

        A = [column(v) for v in (indSetA if isinstance(indSetA, (list, tuple, np.ndarray)) else [indSetA])]
        B = [column(v) for v in (indSetB if isinstance(indSetB, (list, tuple, np.ndarray)) else [indSetB])]
        fa, fb = np.broadcast_to(np.asarray(factorA, dtype=float), (len(A),)), np.broadcast_to(np.asarray(factorB, dtype=float), (len(B),))
        if len(A) != len(B) or not A:
            raise ValueError(f"linear constraints {name!r}: indSetA and indSetB must pair up ({len(A)} and {len(B)} variables)")
        if not (np.all(np.isfinite(fa)) and np.all(np.isfinite(fb))):
            raise ValueError(f"linear constraints {name!r}: the factors must be finite")
        if any(a == b for a, b in zip(A, B)):
            raise ValueError(f"linear constraints {name!r}: a variable is paired with itself")
        M = np.zeros((len(A), len(names)))
        for i, (a, b) in enumerate(zip(A, B)):
            M[i, a] += fa[i]
            M[i, b] += fb[i]
        if np.any(np.all(M == 0, axis=1)):
            raise ValueError(f"linear constraints {name!r}: a row has zero factors: no design variable influences it")

        def evaluate(X, gradient=True):
            p = np.array([self.dvs.getValues()[n] for n in names])
            return M @ p, None

        self._add(_Constraint(name, 'linear', _finite_bound(lower, 'lower'), _finite_bound(upper, 'upper'), False, evaluate, M))

    def addLeTeConstraints(self, name, indSetA, indSetB):
        """The leading or trailing edge held (pyGeo's addLeTeConstraints): for each pair of local
        variables the midpoint of their control points does not move, p_A a_A + p_B a_B = 0,
        a linear constraint p_A + s p_B = 0 with s = sign(a_A . a_B) (their directions must be
        parallel: opposite normals on an upper and a lower surface give p_A = p_B, pyGeo's equal
        directions p_A + p_B = 0)."""
        controls = self.dvs.getControlPoints()
        A = indSetA if isinstance(indSetA, (list, tuple)) else [indSetA]
        B = indSetB if isinstance(indSetB, (list, tuple)) else [indSetB]
        factors = []
        for a, b in zip(A, B):
            if a not in controls or b not in controls:
                raise ValueError(f"leading/trailing-edge constraints {name!r}: {a!r} and {b!r} must be local variables")
            da, db = controls[a][1][0], controls[b][1][0]
            cosine = np.dot(da, db) / (np.linalg.norm(da) * np.linalg.norm(db))
            if abs(cosine) < 0.9:
                raise ValueError(f"leading/trailing-edge constraints {name!r}: the directions of {a!r} and {b!r} are not "
                                 f"parallel (cosine {cosine:.2f}): one linear relation cannot hold their midpoint")
            factors.append(float(np.sign(cosine) * np.linalg.norm(db) / np.linalg.norm(da)))
        self.addLinearConstraintsShape(name, A, B, 1.0, factors, 0.0, 0.0)

    def addMeshVolumeConstraint(self, name, cells=None, density=None, lower=1.0, upper=3.0, scaled=True):
        """The volume of the volume mesh's cells, or with ``density`` their mass (density times
        the volume): of the cell set ``cells`` (the name of a cell array, 1 in the set: a deck's
        element set as the Mesh File reader gives it) or of every 3D cell. Each cell as its solver
        measures it: linear and quadratic tetrahedra, hexahedra and wedges as CalculiX integrates
        the isoparametric element (its MASS), other cells (a CFD mesh's polyhedra) as OpenFOAM
        does, by pyramids on its faces. Scaled by the baseline by default (lower=1.0: at least the
        baseline's)."""
        self._check_name(name)
        if cells is not None and (not isinstance(cells, str) or not cells):
            raise ValueError(f"mesh volume constraint {name!r}: cells is the name of a cell set (a cell array), not {cells!r}")
        if density is not None:
            density = float(density)
            if not (math.isfinite(density) and density > 0):
                raise ValueError(f"mesh volume constraint {name!r}: density must be a positive finite number, not {density!r}")
        algorithm = self.dvs._algorithm
        factor = 1.0 if density is None else density

        def evaluate(X, gradient=True):
            value, g = self._computed(lambda v, r, d: algorithm.ComputeMeshVolume(cells or '', v, r, d), gradient)
            return np.array([factor * value.GetValue(0)]), None if g is None else [(g[0], factor * g[1])]

        self._add(_Constraint(name, 'meshVolume', lower, upper, scaled, evaluate))

    def addMeshQualityConstraint(self, name, measure='nonOrthogonality', upper=None, lower=None, rho=None, scaled=False):
        """The mesh's quality as one smooth function (DAFoam's KS-aggregated mesh quality): the
        KS aggregate of a measure over the faces of the CFD volume meshes (checkMesh's
        definitions: 'nonOrthogonality' in degrees over every interior face, 'skewness' over every
        interior and boundary face, a boundary face's with its owner mirrored across it), in the
        max-shifted form
        KS = m + ln(sum_f exp(rho (q_f - m))) / rho, m the largest q_f, so that
        m <= KS <= m + ln(N) / rho (N faces); or of the least scaled Jacobian of an FEM mesh's
        elements at their corners and integration points ('scaledJacobian', the FEM verdict's:
        -KS of -sj, so that least - ln(N) / rho <= value <= least). ``getBiasBound(name)`` gives
        ln(N) / rho. rho defaults to 10 per degree (non-orthogonality) or 100. Absolute values by
        default (upper=70 degrees as checkMesh's; lower=0.2 for the scaled Jacobian). Needs the
        filter's MeshQuality on. Under MPI the faces between the processes' pieces are measured
        across them (as checkMesh measures a processor patch): the serial value."""
        self._check_name(name)
        measures = ('nonOrthogonality', 'skewness', 'scaledJacobian')
        if measure not in measures:
            raise ValueError(f"mesh quality constraint {name!r}: measure is one of {', '.join(measures)}, not {measure!r}")
        rho = (10.0 if measure == 'nonOrthogonality' else 100.0) if rho is None else float(rho)
        if not (math.isfinite(rho) and rho > 0):
            raise ValueError(f"mesh quality constraint {name!r}: rho must be a positive finite number, not {rho!r}")
        algorithm = self.dvs._algorithm
        index = measures.index(measure)
        constraint = None

        def evaluate(X, gradient=True):
            value, g = self._computed(lambda v, r, d: algorithm.ComputeMeshQualityAggregate(index, rho, v, r, d), gradient)
            constraint.count = int(value.GetValue(1))
            return np.array([value.GetValue(0)]), None if g is None else [g]

        constraint = _Constraint(name, 'meshQuality', lower, upper, scaled, evaluate)
        constraint.rho = rho
        self._add(constraint)

    def getBiasBound(self, name):
        """A mesh-quality constraint's bound on |KS - the extreme|: ln(N) / rho (N faces or element points)."""
        c = self._constraints[name]
        return math.log(max(1, c.count)) / c.rho

    # -- evaluation (pyGeo's) -----------------------------------------------------------------
    def getConstraintNames(self):
        return list(self._constraints)

    def getBounds(self):
        """{name: (lower, upper)} in the units evalFunctions gives (None: unbounded)."""
        return {n: (c.lower, c.upper) for n, c in self._constraints.items()}

    def evalFunctions(self, funcs, includeLinear=True):
        """funcs[name] = the constraint's values (an array) at the current design variables.
        includeLinear=False leaves out the linear relations (pyGeo's default: an optimizer that
        takes them once as linear constraints, their constant rows from evalFunctionsSens)."""
        for name, values in self._state(gradients=False)['values'].items():
            if includeLinear or self._constraints[name].linear is None:
                funcs[name] = values

    def evalFunctionsSens(self, funcsSens, includeLinear=True):
        """funcsSens[name] = {design variable: d(values)/dp (an array)}: every gradient chained
        through the reverse mode at once (one gathering of their points, one back-substitution
        per value, whatever the number of variables); includeLinear as for evalFunctions."""
        names = self.dvs.getVarNames()
        for name, J in self._state(gradients=True)['jacobians'].items():
            if includeLinear or self._constraints[name].linear is None:
                funcsSens[name] = {v: column for v, column in zip(names, J.T)}

    def getScipyConstraints(self):
        """Constraint dicts for scipy.optimize.minimize (SLSQP, trust-constr's old form) over the
        vector x of the design variables in getVarNames() order: 'eq' for lower == upper, else
        'ineq' (value - lower >= 0, upper - value >= 0), each with its 'jac'. fun(x) and jac(x)
        set the variables to x (setDesignVars) when they differ, clipped to their bounds
        (trust-constr tries points beyond them: clip x in the objective too, np.clip)."""
        out = []
        for name, c in self._constraints.items():
            sides = [(1.0, c.lower)] if c.lower is not None and c.lower == c.upper else \
                [(s, b) for s, b in ((1.0, c.lower), (-1.0, c.upper)) if b is not None]
            kind = 'eq' if c.lower is not None and c.lower == c.upper else 'ineq'
            for s, bound in sides:
                out.append({'type': kind, 'fun': self._scipy_value(c, s, bound), 'jac': self._scipy_jacobian(c, s)})
        return out

    # -- internals ----------------------------------------------------------------------------
    def _computed(self, compute, gradient):
        """A function the filter computes: compute(value, rows, g) fills value (a vtkDoubleArray,
        the value first) and, when rows and g are given, dF/dX at the output points where it is
        not zero (their indices, their values). Returns value and, when asked, the gradient as
        (rows, values)."""
        from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIdTypeArray
        from vtkmodules.util.numpy_support import vtk_to_numpy
        value, rows, g = vtkDoubleArray(), vtkIdTypeArray(), vtkDoubleArray()
        if not compute(value, *((rows, g) if gradient else (None, None))):
            raise RuntimeError(self.dvs._algorithm.GetSensitivityError())
        if not gradient:
            return value, None
        return value, (vtk_to_numpy(rows).astype(np.int64), vtk_to_numpy(g).reshape(-1, 3).astype(float))

    def _set(self, x):
        """The variables set to x, clipped to their bounds: an optimizer's trial point may lie
        beyond them (trust-constr's), where the functions continue as at the bound."""
        names = self.dvs.getVarNames()
        x = np.asarray(x, dtype=float).reshape(-1)
        if len(x) != len(names):
            raise ValueError(f"x has {len(x)} entries; the design has {len(names)} variables")
        if not np.all(np.isfinite(x)):
            raise ValueError("x has values that are not finite")
        bounds = self.dvs.getBounds()
        x = np.clip(x, [-math.inf if bounds[n][0] is None else bounds[n][0] for n in names],
                    [math.inf if bounds[n][1] is None else bounds[n][1] for n in names])
        current = self.dvs.getValues()
        changed = {n: v for n, v in zip(names, x) if current[n] != v}
        if changed:
            self.dvs.setDesignVars(changed)

    def _scipy_value(self, c, sign, bound):
        def fun(x):
            self._set(x)
            return sign * (self._state(gradients=False)['values'][c.name] - bound)
        return fun

    def _scipy_jacobian(self, c, sign):
        def jac(x):
            self._set(x)
            return sign * self._state(gradients=True)['jacobians'][c.name]
        return jac

    def _state(self, gradients):
        """The constraints' values (scaled as asked) and, when asked, their jacobians (m x ndv) at
        the current design, computed once per design (and per update of the filter's output)."""
        self.dvs._updated()
        key = (tuple(self.dvs.getValues().items()), self.dvs._algorithm.GetOutputDataObject(0).GetMTime(), tuple(self._constraints))
        if self._cache is None or self._cache['key'] != key:
            self._cache = {'key': key, 'X': self.dvs.update(), 'values': None, 'jacobians': None}
        state = self._cache
        if state['values'] is None or (gradients and state['jacobians'] is None):
            state['values'], state['jacobians'] = self._evaluate(list(self._constraints.values()), state['X'], gradients)
        return state

    def _evaluate(self, constraints, X, gradients):
        """{name: values} and (gradients) {name: jacobian}, the geometric ones chained at once."""
        values, pending, jacobians = {}, [], {}
        for c in constraints:
            v, g = c.evaluate(X, gradient=gradients and c.linear is None)
            values[c.name] = v / c.baseline if c.scaled and c.baseline is not None else v
            if gradients:
                if c.linear is not None:
                    jacobians[c.name] = c.linear.copy()
                else:
                    pending.append((c, g))
        if pending:
            names = self.dvs.getVarNames()
            chained = iter(self.dvs.totalSensitivities([self._consolidated(X, g) for _, gs in pending for g in gs]))
            for c, gs in pending:
                J = np.array([[d[n] for n in names] for d in (next(chained) for _ in gs)]).reshape(len(gs), len(names))
                jacobians[c.name] = J / c.baseline[:, None] if c.scaled and c.baseline is not None else J
        return values, (jacobians if gradients else None)

    @staticmethod
    def _consolidated(X, g):
        """Under MPI: a gradient (points, values) with each position's values summed over the
        processes, on one copy of it per process (the reverse mode counts a position once over
        the processes, summed over its copies on one process); g itself on one process."""
        if controller() is None:
            return g
        rows, values = g
        positions = all_gather(X[rows].reshape(-1)).reshape(-1, 3)
        values = all_gather(np.asarray(values).reshape(-1)).reshape(-1, 3)
        ids = _position_ids(np.concatenate([positions, X]))
        theirs, mine = ids[:len(positions)], ids[len(positions):]
        total = np.zeros((int(ids.max(initial=-1)) + 1, 3))
        np.add.at(total, theirs, values)
        # one copy of a position on this process carries its total: its first point there
        held, first = np.unique(mine, return_index=True)
        out_rows = np.sort(first[np.isin(held, theirs)]).astype(np.int64)
        return out_rows, total[mine[out_rows]]

    def _thickness(self, name, at, directions, surface, lower, upper, scaled):
        what = f"thickness constraints {name!r}"
        self._check_name(name)
        surf = self._surface(surface, what)
        X = self._points()
        ends = []   # per line, per side: (process holding the hit, triangle, barycentric weights)
        for p, u in zip(at, directions):
            sides = []
            for side in (1.0, -1.0):
                t, tri, w = self._cast(surf, X, p, side * u)
                best = all_reduce(t, 'min')
                owner = all_reduce(rank() if t == best else 1 << 30, 'min') if math.isfinite(best) else None
                sides.append((owner, tri, w))
            hits = sum(owner is not None for owner, _, _ in sides)
            if hits < 2:
                raise ValueError(f"{what}: the line through {list(p)} along {list(u)} "
                                 f"{'hits the surface on one side only' if hits else 'misses the surface'}: put the point "
                                 "inside the body, between its surfaces")
            ends.append(sides)
        me = rank()

        def end(X, owner, tri, w):
            x = np.zeros(3) if owner != me else w @ X[surf.triangles[tri]]
            return all_reduce(x, 'sum')

        def evaluate(X, gradient=True):
            values, grads = [], []
            for (top, bottom) in ends:
                a, b = end(X, *top), end(X, *bottom)
                d = a - b
                values.append(np.linalg.norm(d))
                if gradient:
                    rows, g = [], []
                    unit = d / values[-1]
                    for (owner, tri, w), s in ((top, 1.0), (bottom, -1.0)):
                        if owner == me:
                            rows += list(surf.triangles[tri])
                            g += [s * w[k] * unit for k in range(3)]
                    grads.append((np.array(rows, dtype=np.int64), np.array(g).reshape(-1, 3)))
            return np.array(values), (grads if gradient else None)

        self._add(_Constraint(name, 'thickness', lower, upper, scaled, evaluate))

    @staticmethod
    def _cast(surf, X, p, u):
        """The nearest hit of the ray p + t u (t > 0) with the surface's triangles on this process:
        (t, triangle, barycentric weights), t = inf when it misses (Moeller-Trumbore)."""
        x0, x1, x2 = surf.corners(X)
        e1, e2 = x1 - x0, x2 - x0
        h = np.cross(u, e2)
        det = np.einsum('ij,ij->i', e1, h)
        scale = np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1)
        ok = np.abs(det) > 1e-12 * scale
        det = np.where(ok, det, 1)
        s = p - x0
        b1 = np.einsum('ij,ij->i', s, h) / det
        q = np.cross(s, e1)
        b2 = (q @ u) / det
        t = np.einsum('ij,ij->i', e2, q) / det
        tolerance = 1e-10
        hit = ok & (b1 >= -tolerance) & (b2 >= -tolerance) & (b1 + b2 <= 1 + tolerance) & (t > 0)
        if not hit.any():
            return math.inf, -1, None
        i = int(np.flatnonzero(hit)[np.argmin(t[hit])])
        return float(t[i]), i, np.array([1 - b1[i] - b2[i], b1[i], b2[i]])

    @staticmethod
    def _check_closed(surf, X, axis, what):
        """Raises ValueError unless every triangle edge (by its end positions, over all processes)
        is run as often one way as the other (the divergence theorem's closed surface); with an
        axis, edges on the surface's front and back (the extremes along the axis) may be open."""
        tri = surf.triangles
        directed = np.concatenate([np.stack([tri[:, k], tri[:, (k + 1) % 3]], axis=1) for k in range(3)])
        ends = np.concatenate([X[directed[:, 0]], X[directed[:, 1]]], axis=1)
        ends = all_gather(ends.reshape(-1)).reshape(-1, 6)
        if axis is not None:
            along = np.concatenate([ends[:, :3] @ axis, ends[:, 3:] @ axis])
            low, high = along.min(), along.max()
            tol = 1e-9 * max(1.0, np.abs(along).max())
            a, b = ends[:, :3] @ axis, ends[:, 3:] @ axis
            cap = ((np.abs(a - low) <= tol) & (np.abs(b - low) <= tol)) | ((np.abs(a - high) <= tol) & (np.abs(b - high) <= tol))
            ends = ends[~cap]
        # closed as a chain: each edge run as often one way as the other (a pinched, non-manifold
        # spot of a snapped surface, where four triangles meet at an edge, is closed too): per
        # distinct edge, its runs against its reverse's (+ 0.0: -0 and 0 are one coordinate)
        position = _position_ids(np.concatenate([ends[:, :3], ends[:, 3:]]))
        a, b = position[:len(ends)], position[len(ends):]
        count = int(position.max(initial=-1)) + 1
        _, inverse = np.unique(np.concatenate([a * count + b, b * count + a]), return_inverse=True)
        inverse = inverse.reshape(-1)
        runs = np.bincount(inverse[:len(ends)], minlength=int(inverse.max(initial=-1)) + 1)
        back = np.bincount(inverse[len(ends):], minlength=len(runs))
        unmatched = int(np.abs(runs - back)[runs > 0].sum())
        if unmatched:
            raise ValueError(f"{what}: the surface is not closed ({unmatched} of its {len(ends)} triangle edges have no "
                             "partner run the other way): an enclosed volume needs a closed surface"
                             + ("" if axis is not None else " (an extruded 2D shape: give axis=)"))

    def _direction(self, axis, name):
        a = np.asarray(axis, dtype=float).reshape(-1)
        if a.shape != (3,) or not np.all(np.isfinite(a)) or not np.any(a):
            raise ValueError(f"constraint {name!r}: the direction must be 3 finite numbers, not zero, not {axis!r}")
        return a / np.linalg.norm(a)

    def _check_name(self, name):
        if not isinstance(name, str) or not name:
            raise ValueError(f"a constraint's name must be a non-empty string, not {name!r}")
        if name in self._constraints:
            raise ValueError(f"constraint {name!r} is defined already")

    def _surface(self, names, what):
        """The _Surface of the named blocks, one per names for all the constraints on it (so that
        they share its corners on a design's points)."""
        key = names if names is None or isinstance(names, str) else tuple(names)
        if key not in self._surfaces:
            self._surfaces[key] = _Surface(self._output(), names, what)
        return self._surfaces[key]

    def _output(self):
        self.dvs._updated()
        return self.dvs._algorithm.GetOutputDataObject(0)

    def _points(self):
        return self.dvs.update()

    def _add(self, c):
        """Checks the bounds, takes the baseline and checks that some variable influences every
        value; adds the constraint only then."""
        c.lower = _finite_bound(c.lower, f"constraint {c.name!r}: lower")
        c.upper = _finite_bound(c.upper, f"constraint {c.name!r}: upper")
        if c.lower is not None and c.upper is not None and c.lower > c.upper:
            raise ValueError(f"constraint {c.name!r}: lower ({c.lower}) exceeds upper ({c.upper})")
        X = self._points()
        try:
            values, _ = c.evaluate(X, gradient=False)
        except RuntimeError as e:
            raise ValueError(f"constraint {c.name!r}: {e}") from None
        if not np.all(np.isfinite(values)):
            raise ValueError(f"constraint {c.name!r}: its baseline values are not finite")
        if c.scaled and np.any(values == 0):
            raise ValueError(f"constraint {c.name!r}: a baseline value is 0, so it cannot be scaled: give scaled=False")
        c.baseline = values.copy()
        J = self._evaluate([c], X, True)[1][c.name]
        # a gradient below the value's round-off (1e-12 of it per unit of every variable) is no
        # influence: terms that cancel leave round-off, not a dependence
        dead = np.flatnonzero(np.all(np.abs(J) <= 1e-12 * np.abs(values)[:, None], axis=1))
        if len(dead):
            raise ValueError(f"constraint {c.name!r}: no design variable influences its value{'s' if len(dead) > 1 else ''} "
                             f"{', '.join(map(str, dead[:10]))} (the gradient is zero): the points it measures do not move "
                             "with the design")
        self._constraints[c.name] = c
        self._cache = None
