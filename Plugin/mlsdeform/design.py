"""Design variables on an MLS Deform filter's Handle regions, and exact sensitivities.

Output order: the points of every array this module returns or takes (``update()``,
``totalSensitivityProd``, ``totalSensitivity``) are the MLS Deform output's points, block after
block in the order a composite iterator visits the leaves (for an OpenFOAM case read with
*Decompose polyhedra* off: the internal mesh in polyMesh order first, then the patches), and
within a block in the block's order. Under MPI (``pvbatch --symmetric``: every process runs the
script) each process sees its own part of the output; ``totalSensitivity`` and
``checkDerivatives`` return the global values on every process.
"""
import math

import numpy as np

from .deformer import _load_wrapping, deformer as _deformer
from .ranks import all_reduce

# The kinds of design variable, in the order of vtkConstraintRegion's kind numbers
# (Filters/Adapters/DesignVariables.h: DesignKindNames).
KINDS = ("translate", "rotate", "scale", "local")
_UNBOUNDED = 1e300  # a missing bound (the filter needs finite numbers)


def _vector(value, what, zero=False):
    try:
        v = [float(x) for x in value]
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be 3 numbers, not {value!r}") from None
    if len(v) != 3 or not all(math.isfinite(x) for x in v):
        raise ValueError(f"{what} must be 3 finite numbers, not {value!r}")
    if not zero and not any(v):
        raise ValueError(f"{what} must not be zero: it is the variable's direction times its coefficient")
    return v


def _check_finite(name, value):
    if not math.isfinite(value):
        raise ValueError(f"design variable {name!r}: the value {value} is not finite")


class DesignVariables:
    """The design variables of one MLS Deform filter: a paraview.simple proxy, or a
    vtkMLSDeformFilter on a plain VTK pipeline (mlsdeform.vtkfoam) with vtkConstraintRegions.

    Variables live on the Handle regions (their DesignVariables property), so they are saved with
    a ParaView state and found again: ``DesignVariables(deformer)`` reads the ones its regions
    already have.
    """

    def __init__(self, deformer):
        self.deformer = deformer
        self._filter = _deformer(deformer)
        self._algorithm = self._filter.algorithm
        # name -> {"kind", "regions": [region], "axes": [[x, y, z]], "value", "lower", "upper"}, in definition order
        self._variables = {}
        for region in self._filter.regions():
            for name, (kind, x, y, z, value, lower, upper) in self._filter.rows(region):
                entry = self._variables.setdefault(name, {"kind": KINDS[int(kind)], "regions": [], "axes": [], "value": value,
                                                          "lower": lower, "upper": upper})
                entry["regions"].append(region)
                entry["axes"].append([x, y, z])

    # -- definition -------------------------------------------------------------------------
    def addHandleDV(self, name, regions, translate=None, rotate=None, scale=None, lower=None, upper=None, value=0.0):
        """A design variable p on one Handle region or several (a list): exactly one of
        ``translate`` (a direction in model units per unit of p), ``rotate`` (an axis through the
        region's pivot; its length is degrees per unit of p) or ``scale`` (an axis along which the
        scale factor grows by p times its length). With several regions give one vector for all,
        or a list of one per region (e.g. [[0, 1, 0], [0, -1, 0]] for a symmetric pair).
        ``lower``/``upper`` bound p (None: unbounded); ``value`` is its start (default 0: the
        motion as typed). Raises ValueError and changes nothing when an argument is wrong."""
        self._check_name(name)
        given = [(k, v) for k, v in zip(KINDS, (translate, rotate, scale)) if v is not None]
        if len(given) != 1:
            raise ValueError("give exactly one of translate=, rotate= or scale=")
        kind, axes = given[0]
        regions = list(regions) if isinstance(regions, (list, tuple)) else [regions]
        if not regions:
            raise ValueError("a design variable needs at least one Handle region")
        axes = np.asarray(axes, dtype=float)
        if axes.ndim == 1:
            axes = np.tile(axes, (len(regions), 1))
        if axes.shape != (len(regions), 3):
            raise ValueError(f"{kind}= needs one 3-vector, or one per region ({len(regions)}), not shape {axes.shape}")
        axes = [_vector(a, f"the {kind} axis of {name!r}") for a in axes]
        lower, upper, value = self._bounds(name, lower, upper, value)
        key = self._filter.key
        for region in regions:
            self._check_handle(name, region)
            if any(v["kind"] == "local" and key(v["regions"][0]) == key(region) for v in self._variables.values()):
                raise ValueError(f"design variable {name!r}: this region holds the control points of local variables, "
                                 "not a body: move the body with another Handle region")
        if len(set(key(r) for r in regions)) != len(regions):
            raise ValueError(f"design variable {name!r}: a region is named twice")
        self._variables[name] = {"kind": kind, "regions": regions, "axes": axes, "value": value, "lower": lower, "upper": upper}
        self._write(regions)

    def addLocalDV(self, name, region, count=None, points=None, direction="normal", axis=None, mirror=None,
                   lower=None, upper=None, value=0.0):
        """Local shape variables on a Handle region (pyGeo's addLocalDV): control points, each its
        own variable ``name_0``, ``name_1``, ... (returned, in the order of the points), holding
        its point at x + p a while every other point of the region is free, so the surface between
        control points bends smoothly (a bump about as wide as their spacing).

        ``count``: that many control points spread evenly over the region's points
        (farthest-point sampling, deterministic); or ``points``: an (n, 3) array of positions,
        each snapped to the region's nearest point (within a tenth of the region's size or two
        point spacings there).
        ``direction``: ``'normal'`` (the surface's unit normal there, pointing out of the mesh: on
        a CFD case's wall into the body, on a solid out of it) or a 3-vector (model units per unit
        of p; normal to ``axis`` when that is given). ``axis``: a line axis: each
        control point then holds every region point on the line through it along the axis (the
        depth of a one-cell-thick 2D case, a plate's thickness), so an extruded shape stays
        extruded. ``mirror``: ``(origin, normal)`` of a plane: each control point gets its mirror
        image, moved by the same variable (the direction mirrored). ``lower``/``upper`` bound
        every variable (None: unbounded), ``value`` is their start (default 0: in place).
        Raises ValueError and changes nothing when an argument is wrong or the control points do
        not fit the region (more than its points, two on one point, no surface for a normal)."""
        self._check_name(name)
        if (count is None) == (points is None):
            raise ValueError(f"local variables {name!r}: give count= or points=, not both or neither")
        lower, upper, value = self._bounds(name, lower, upper, value)
        self._check_handle(name, region)
        key = self._filter.key
        if any(v["kind"] != "local" and any(key(r) == key(region) for r in v["regions"]) for v in self._variables.values()):
            raise ValueError(f"local variables {name!r}: this region's motion has design variables already; "
                             "control points need a Handle region of their own (its other points are free)")
        normal = isinstance(direction, str)
        if normal and direction != "normal":
            raise ValueError(f"local variables {name!r}: direction is 'normal' or a 3-vector, not {direction!r}")
        a = [0.0, 0.0, 0.0] if normal else _vector(direction, f"the direction of {name!r}")
        line = [0.0, 0.0, 0.0] if axis is None else _vector(axis, f"the line axis of {name!r}")
        plane = None
        if mirror is not None:
            try:
                origin, plane_normal = mirror
            except (TypeError, ValueError):
                raise ValueError(f"local variables {name!r}: mirror is (origin, normal) of a plane, not {mirror!r}") from None
            origin = np.array(_vector(origin, "the mirror plane's origin", zero=True))
            plane_normal = np.array(_vector(plane_normal, "the mirror plane's normal"))
            plane = (origin, plane_normal / np.linalg.norm(plane_normal))
        algorithm = self._filter.region_algorithm(region)
        if points is not None:
            positions = np.asarray(points, dtype=float)
            if positions.ndim == 1 and positions.size == 3:
                positions = positions.reshape(1, 3)
            if positions.ndim != 2 or positions.shape[1] != 3 or len(positions) == 0:
                raise ValueError(f"local variables {name!r}: points= must be an (n, 3) array, not shape {positions.shape}")
            if not np.all(np.isfinite(positions)):
                raise ValueError(f"local variables {name!r}: points= has values that are not finite")
        else:
            if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
                raise ValueError(f"local variables {name!r}: count= must be a whole number of at least 1, not {count!r}")
            from vtkmodules.vtkCommonCore import vtkDoubleArray
            spread = vtkDoubleArray()
            if not algorithm.SpreadControlPoints(int(count), *line, spread):
                raise ValueError(f"local variables {name!r}: {algorithm.GetControlPointError()}")
            positions = self._numpy(spread).copy()
        names = [f"{name}_{i}" for i in range(len(positions))]
        taken = [n for n in names if n in self._variables]
        if taken:
            raise ValueError(f"local variables {name!r}: {', '.join(map(repr, taken))} are defined already")
        rows = []
        for n, q in zip(names, positions):
            rows.append((n, list(q) + a + line))
            if plane is not None:
                origin, m = plane
                image = q - 2 * np.dot(q - origin, m) * m
                if np.linalg.norm(image - q) > 1e-9 * max(1.0, np.linalg.norm(q)):  # a point on the plane is its own image
                    mirrored = a if normal else list(np.array(a) - 2 * np.dot(a, m) * m)
                    rows.append((n, list(image) + list(mirrored) + line))
        before = self._filter.controls(region)
        self._filter.write_controls(region, before + rows)
        for n in names:
            self._variables[n] = {"kind": "local", "regions": [region], "axes": [[0.0, 0.0, 0.0]], "value": value,
                                  "lower": lower, "upper": upper}
        self._write([region])
        error = self._region_error(region)
        if error:
            for n in names:
                del self._variables[n]
            self._filter.write_controls(region, before)
            self._write([region])
            raise ValueError(f"local variables {name!r}: {error}")
        return names

    def getControlPoints(self, name=None):
        """{variable: (n, 3) array of the positions its control points hold (snapped; with a line
        axis, every point of the line), and (n, 3) their directions} for the local variables
        (or the one named), from the regions' last update on this process."""
        from vtkmodules.util.numpy_support import vtk_to_numpy
        out = {}
        key = self._filter.key
        regions = {key(v["regions"][0]): v["regions"][0] for n, v in self._variables.items() if v["kind"] == "local"}
        for region in regions.values():
            self._filter.region_algorithm(region)
            data = self._filter.output(region)
            directions = data.GetPointData().GetArray("ControlDirection")
            derivatives = data.GetPointData().GetArray("PrescribedDisplacementDerivatives")
            names = data.GetFieldData().GetAbstractArray("DesignVariableNames")
            if directions is None or derivatives is None or names is None:
                continue
            x = np.array([data.GetPoint(i) for i in range(data.GetNumberOfPoints())]).reshape(-1, 3)
            a = vtk_to_numpy(directions).reshape(-1, 3)
            d = vtk_to_numpy(derivatives).reshape(len(x), -1, 3)
            for j in range(names.GetNumberOfValues()):
                n = names.GetValue(j)
                held = np.any(d[:, j, :] != 0, axis=1)
                if self._variables.get(n, {}).get("kind") == "local" and (name is None or n == name):
                    out[n] = (x[held], a[held])
        return out

    # -- values -----------------------------------------------------------------------------
    def getVarNames(self):
        return list(self._variables)

    def getNDV(self):
        return len(self._variables)

    def getValues(self):
        return {name: v["value"] for name, v in self._variables.items()}

    def getBounds(self):
        """{name: (lower, upper)}, None for an unbounded side (scipy.optimize's convention)."""
        def bound(x):
            return None if abs(x) >= _UNBOUNDED else x
        return {name: (bound(v["lower"]), bound(v["upper"])) for name, v in self._variables.items()}

    def setDesignVars(self, values):
        """Sets the values of the variables named in ``values`` (a dict; the others keep theirs).
        Only the handles' motions change: the deformation's set-up stays cached. Raises
        ValueError and changes nothing for an unknown name, a value that is not finite or one
        outside its bounds."""
        checked = {}
        for name, value in dict(values).items():
            if name not in self._variables:
                raise ValueError(f"unknown design variable {name!r} (known: {', '.join(self._variables) or 'none'})")
            value = float(np.asarray(value).reshape(-1)[0]) if np.ndim(value) else float(value)
            v = self._variables[name]
            _check_finite(name, value)
            if not (v["lower"] <= value <= v["upper"]):
                raise ValueError(f"design variable {name!r}: {value} is outside its bounds [{v['lower']}, {v['upper']}]")
            checked[name] = value
        touched = []
        for name, value in checked.items():
            self._variables[name]["value"] = value
            touched += self._variables[name]["regions"]
        self._write(touched)

    # -- evaluation -------------------------------------------------------------------------
    def update(self):
        """Runs the deformation; returns the output's points as an (n, 3) float64 array in output
        order: the deformation's own x + d(x), not the output's stored (possibly float32) copy.
        Raises RuntimeError with the filter's message when the deformation failed."""
        from vtkmodules.vtkCommonCore import vtkDoubleArray
        self._updated()
        points = vtkDoubleArray()
        self._call(self._algorithm.GetDeformedPoints(points))
        return self._numpy(points)

    def totalSensitivityProd(self, seeds):
        """Forward mode: sum_p seeds[p] dX/dp as an (n, 3) array in output order (one tangent
        solve, whatever the number of variables seeded)."""
        from vtkmodules.vtkCommonCore import vtkDoubleArray
        names = self._updated()
        vector = np.zeros(len(names))
        for name, seed in dict(seeds).items():
            if name not in names:
                raise ValueError(f"unknown design variable {name!r}")
            vector[names.index(name)] = float(seed)
        if not np.all(np.isfinite(vector)):
            raise ValueError("the seeds must be finite")
        array = vtkDoubleArray()
        for x in vector:
            array.InsertNextValue(x)
        out = vtkDoubleArray()
        self._call(self._algorithm.ComputeSensitivityProduct(array, out))
        return self._numpy(out)

    def totalSensitivity(self, dJdX):
        """Reverse mode: dJ/dp = sum_i dJ/dX_i . dX_i/dp for every variable, as a dict, from
        dJdX, an (n, 3) array in output order (zero where J does not depend on a point). One
        back-substitution whatever the number of variables (without iterative constraints)."""
        return self._reverse([dJdX], lambda f: "dJdX")[0]

    def totalSensitivities(self, gradients):
        """Reverse mode for several functions at once: [dJ_f/dp as a dict] from a list of their
        dJ_f/dX, each an (n, 3) array in output order or a pair (rows, values) of point indices
        and their (len(rows), 3) values (the points where J_f depends on X). One gathering of their
        points and of the deformation's rows there, then one back-substitution per function."""
        return self._reverse(gradients, lambda f: f"gradient {f}")

    def _reverse(self, gradients, what):
        """totalSensitivities, what(f) naming gradient f in the errors. A dense gradient goes to
        the filter as its non-zero rows (a surface's on a 1M-point mesh: no copy of all)."""
        from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIdTypeArray
        from vtkmodules.util.numpy_support import numpy_to_vtk
        names = self._updated()
        n = self._algorithm.GetOutputDataObject(0).GetNumberOfPoints()
        rows, values, starts = [], [], [0]
        for f, g in enumerate(gradients):
            if isinstance(g, tuple):
                r, v = np.asarray(g[0], dtype=np.int64).reshape(-1), np.asarray(g[1], dtype=float).reshape(-1, 3)
                if len(r) != len(v) or (len(r) and (r.min() < 0 or r.max() >= n)):
                    raise ValueError(f"{what(f)}: rows must be point indices 0 .. {n - 1}, one per row of values")
            else:
                g = np.asarray(g, dtype=float)
                if g.shape != (n, 3):
                    raise ValueError(f"{what(f)} must be an (n, 3) array with n = {n} (the output's points), not shape {g.shape}")
                # column by column: a third of np.any(g != 0, axis=1)'s time (NaN counts, and is refused below)
                r = np.flatnonzero((g[:, 0] != 0) | (g[:, 1] != 0) | (g[:, 2] != 0))
                v = g[r]
            if not np.all(np.isfinite(v)):
                raise ValueError(f"{what(f)} has values that are not finite (NaN or infinity)")
            rows.append(r)
            values.append(v)
            starts.append(starts[-1] + len(r))
        rows = np.concatenate(rows) if rows else np.zeros(0, dtype=np.int64)
        values = np.ascontiguousarray(np.concatenate(values) if values else np.zeros((0, 3)))
        from vtkmodules.util.vtkConstants import VTK_ID_TYPE
        r_vtk, s_vtk = [numpy_to_vtk(np.asarray(a, dtype=np.int64), deep=1, array_type=VTK_ID_TYPE) if len(a) else vtkIdTypeArray()
                        for a in (rows, starts)]
        v_vtk = numpy_to_vtk(values, deep=1) if len(values) else vtkDoubleArray()
        v_vtk.SetNumberOfComponents(3)
        out = vtkDoubleArray()
        self._call(self._algorithm.ComputeObjectiveSensitivities(r_vtk, v_vtk, s_vtk, out))
        return [{name: out.GetComponent(f, i) for i, name in enumerate(names)} for f in range(len(starts) - 1)]

    def checkDerivatives(self, step=1e-6, verbose=True):
        """Compares each variable's exact dX/dp with the central difference (X(p + h) - X(p - h)) / 2h
        (one-sided next to a bound), prints a table and returns the largest relative difference
        max |FD - exact| / max |exact|. Every value is restored afterwards."""
        start = self.getValues()
        worst = 0.0
        rows = []
        try:
            for name in self.getVarNames():
                v = self._variables[name]
                exact = self.totalSensitivityProd({name: 1.0})
                p = start[name]
                up, down = min(p + step, v["upper"]), max(p - step, v["lower"])
                if up == down:
                    raise ValueError(f"design variable {name!r}: its bounds leave no room for a step of {step}")
                self.setDesignVars({name: up})
                plus = self.update()
                self.setDesignVars({name: down})
                minus = self.update()
                self.setDesignVars({name: p})
                fd = (plus - minus) / (up - down)
                scale = self._global_max(np.abs(exact))
                difference = self._global_max(np.abs(fd - exact))
                relative = difference / scale if scale > 0 else difference
                worst = max(worst, relative)
                rows.append((name, scale, difference, relative))
        finally:
            self.setDesignVars(start)
        if verbose:
            print(f"{'variable':>16} {'max |dX/dp|':>14} {'max |FD - exact|':>18} {'relative':>10}")
            for name, scale, difference, relative in rows:
                print(f"{name:>16} {scale:14.6e} {difference:18.6e} {relative:10.2e}")
        return worst

    # -- internals --------------------------------------------------------------------------
    def _check_name(self, name):
        if not isinstance(name, str) or not name or any(c in name for c in ",\n"):
            raise ValueError(f"a design variable's name must be a non-empty string without commas, not {name!r}")
        if name in self._variables:
            raise ValueError(f"design variable {name!r} is defined already")

    @staticmethod
    def _bounds(name, lower, upper, value):
        lower = -_UNBOUNDED if lower is None else float(lower)
        upper = _UNBOUNDED if upper is None else float(upper)
        value = float(value)
        _check_finite(name, value)
        if not (math.isfinite(lower) and math.isfinite(upper)) or lower > upper:
            raise ValueError(f"design variable {name!r}: lower ({lower}) must not exceed upper ({upper}), both finite")
        if not (lower <= value <= upper):
            raise ValueError(f"design variable {name!r}: the value {value} is outside its bounds [{lower}, {upper}]")
        return lower, upper, value

    def _check_handle(self, name, region):
        if isinstance(region, str):
            raise ValueError(f"design variable {name!r}: its regions are MLS Deform's Handle regions (e.g. deformed.Regions[0]), "
                             f"not patch or set names ({region!r})")
        if self._filter.key(region) not in {self._filter.key(c) for c in self._filter.regions()}:
            raise ValueError(f"design variable {name!r}: a region is not among this MLS Deform's Regions inputs")
        role = self._filter.role(region)
        if role != _load_wrapping().vtkConstraintRegion.Handle:
            raise ValueError(f"design variable {name!r}: it acts on a Handle region's motion, not on a region of role "
                             f"{_load_wrapping().vtkConstraintRegion.GetRoleName(role)}")

    def _region_error(self, region):
        """The region's failure after an update ('' when it succeeded)."""
        self._filter.region_algorithm(region)
        error = self._filter.output(region).GetFieldData().GetAbstractArray("DeformationError")
        return error.GetValue(0) if error is not None and error.GetNumberOfValues() > 0 else ""

    def _write(self, regions):
        # each touched region's design-variable rows rewritten from the table, in definition order
        key = self._filter.key
        for k, region in {key(r): r for r in regions}.items():
            self._filter.write(region, [(name, [KINDS.index(v["kind"])] + list(axis) + [v["value"], v["lower"], v["upper"]])
                                        for name, v in self._variables.items()
                                        for r, axis in zip(v["regions"], v["axes"]) if key(r) == k])

    def _updated(self):
        """Brings the filter up to date; raises RuntimeError on a failure; the variables' names in
        the filter's column order."""
        self._filter.update()
        output = self._algorithm.GetOutputDataObject(0)
        error = output.GetFieldData().GetAbstractArray("DeformationError") if output else None
        if error is not None and error.GetNumberOfValues() > 0:
            raise RuntimeError(f"the deformation failed: {error.GetValue(0)}")
        names = output.GetFieldData().GetAbstractArray("DesignVariableNames")
        columns = [names.GetValue(i) for i in range(names.GetNumberOfValues())] if names is not None else []
        if sorted(columns) != sorted(self._variables):
            raise RuntimeError(f"the filter's design variables {columns} are not this object's {list(self._variables)}")
        return columns

    def _call(self, succeeded):
        if not succeeded:
            raise RuntimeError(self._algorithm.GetSensitivityError())

    @staticmethod
    def _numpy(array):
        # a view of the VTK array's memory (it keeps the array alive): no copy of n x 3 doubles
        from vtkmodules.util.numpy_support import vtk_to_numpy
        return vtk_to_numpy(array).reshape(-1, 3)

    @staticmethod
    def _global_max(values):
        return float(all_reduce(float(values.max()) if values.size else 0.0, 'max'))
