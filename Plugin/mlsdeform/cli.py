"""The command line of a design of experiments on an OpenFOAM case or an FEM deck (mlsdeform-doe.py
beside the plugin runs it in Debian's python3 or in pvpython, and from any other python3 hands
itself to one of those):

    python3 .../plugins/MLSDeform/mlsdeform-doe.py DESIGN.json FOLDER (--samples N [--seed S] | --table CSV)
        [--write-failed] [--copy] [--max-non-orthogonality 70] [--max-skewness 4] [--max-inverted-cells 0]
        [--min-scaled-jacobian 0.1]

It builds a plain VTK pipeline (mlsdeform.vtkfoam, mlsdeform.meshfile), without ParaView's server
manager: less memory and a faster start than paraview.simple, and the same variants.

DESIGN.json names the case (or the deck), its patches (or sets) by role and the design variables, e.g.

    {"case": "hull/case.foam", "handle": ["hull"], "fixed": ["inlet", "outlet"],
     "slip": ["sideYmin", "sideYmax", "bottom", "top"],
     "variables": [{"name": "dx", "translate": [1, 0, 0], "lower": -0.1, "upper": 0.1},
                   {"name": "yaw", "rotate": [0, 0, 1], "lower": -5, "upper": 5}],
     "settings": {"NumberOfSamples": 1000}}

    {"deck": "plate/plate.inp", "handle": ["hole1"], "fixed": ["fixed", "load"],
     "variables": [{"name": "x1", "translate": [1, 0, 0], "lower": -0.5, "upper": 0.5}]}

A role's patches are names, patterns of whole names ("motorBike.*") or patch groups
("motorBikeGroup"), as OpenFOAM takes them; a deck's are its node and element sets (*NSET, *ELSET,
*SURFACE) by name. The handle's patches move as one body (one pivot for
rotations and scales); several bodies are named in "handles" instead of "handle", e.g.
{"bike": ["motorBikeGroup"], "rider": ["rider.*"]}, and a variable acts on the bodies it names in
its own "handles" (default: all of them), with one axis for all or one per body. A variable with
"local" instead of an axis is a set of local shape variables on one body (DesignVariables.addLocalDV:
its control points hold the body's surface there, the rest of it is free), named name_0, name_1, ...,
e.g. {"name": "bump", "local": {"count": 8, "direction": "normal"}, "handles": ["hull"], "lower": -0.01,
"upper": 0.01}; its keys are count or points, and optionally direction, axis and mirror. Slip patches each
slide in their own plane. "settings" are MLS Deform properties (the VTK filter's Set<Name>):
numbers, or an enumeration value by its name in the VTK class ("Basis": "Wendland"). A relative
"case" or "deck" is relative to the design file. A case's variants get checkMesh's verdict
(--max-...), a deck's an FEM solver's (--max-inverted-cells, --min-scaled-jacobian). Exit code 0
when every variant was made (whatever their verdicts), 1 on a failure, 2 on a bad design or
command line, with the message on stderr. Running it again resumes.
"""
import argparse
import json
import os
import sys

KEYS = {'case', 'deck', 'handle', 'handles', 'fixed', 'slip', 'variables', 'settings'}
VARIABLE_KEYS = {'name', 'translate', 'rotate', 'scale', 'local', 'lower', 'upper', 'value', 'handles'}
LOCAL_KEYS = {'count', 'points', 'direction', 'axis', 'mirror'}  # DesignVariables.addLocalDV's


def _names(value):
    """A role's or a body's patches: a name or a non-empty list of names, else None."""
    if isinstance(value, str) and value:
        return [value]
    if isinstance(value, list) and value and all(isinstance(v, str) and v for v in value):
        return value
    return None


def setUp(design_path):
    """The MLS Deform of the design file's case with its design variables (mlsdeform.DesignVariables)."""
    from . import DesignVariables, meshfile, vtkfoam
    with open(design_path) as f:
        try:
            design = json.load(f)
        except json.JSONDecodeError as e:
            raise ValueError(f"{design_path}: not JSON: {e}") from None
    unknown = sorted(set(design) - KEYS) if isinstance(design, dict) else []
    if unknown:
        import difflib
        meant = {k: difflib.get_close_matches(k, sorted(KEYS), 1) for k in unknown}
        raise ValueError(f"{design_path}: unknown key" + ('s ' if len(unknown) > 1 else ' ') + ', '.join(
            repr(k) + (f" (did you mean {meant[k][0]!r}?)" if meant[k] else '') for k in unknown) +
            f"; a design's keys are {', '.join(sorted(KEYS))}")
    if not isinstance(design, dict) or 'variables' not in design or ('case' in design) == ('deck' in design) or \
            set(design) - KEYS or ('handle' in design) == ('handles' in design):
        raise ValueError(f"{design_path}: a design needs 'variables', either 'case' (an OpenFOAM case) or 'deck' (an "
                         f"FEM deck) and either 'handle' (the patches or sets of one body) or 'handles' (named bodies), "
                         f"and may have 'fixed', 'slip', 'settings'; not {sorted(design) if isinstance(design, dict) else design!r}")
    bodies = design['handles'] if 'handles' in design else {'handle': design['handle']}
    if not isinstance(bodies, dict) or not bodies or any(_names(p) is None for p in bodies.values()):
        raise ValueError(f"{design_path}: 'handles' maps each body's name to its patches (names, patterns, groups), "
                         f"'handle' lists one body's; not {bodies!r}")
    bodies = {name: _names(p) for name, p in bodies.items()}
    roles = {role: _names(design.get(role, [])) or [] for role in ('fixed', 'slip')}
    source = os.path.join(os.path.dirname(os.path.abspath(design_path)), design.get('case', design.get('deck')))
    if not os.path.exists(source):
        raise ValueError(f"{design_path}: the {'case' if 'case' in design else 'deck'} {source} does not exist")
    names = [n for patches in bodies.values() for n in patches] + roles['fixed'] + roles['slip']
    if 'deck' in design:
        reader = meshfile.open_mesh(source)
    else:
        reader = vtkfoam.open_case(source, names, decompose_polyhedra=False)  # checkMesh's own cells
    deformer = vtkfoam.morph(reader, bodies, (0, 0, 0), roles['fixed'], roles['slip'], **design.get('settings', {}))
    regions = {name: deformer.GetInputAlgorithm(1, i) for i, name in enumerate(bodies)}  # morph() connects the bodies first
    dvs = DesignVariables(deformer)
    for variable in design['variables']:
        if isinstance(variable, dict) and 'patches' in variable:
            raise ValueError(f"{design_path}: variable {variable.get('name')!r} names 'patches': a handle's patches move as "
                             f"one body now; name several bodies in 'handles' and the variable's bodies in its 'handles'")
        if not isinstance(variable, dict) or set(variable) - VARIABLE_KEYS or 'name' not in variable:
            raise ValueError(f"{design_path}: a variable has a name, one of translate/rotate/scale, lower, upper and "
                             f"optionally value and handles, not {variable!r}")
        named = variable.get('handles', list(bodies))
        unknown = [b for b in named if b not in bodies] if isinstance(named, list) else [named]
        if unknown or not named:
            raise ValueError(f"{design_path}: variable {variable['name']!r} names the bodies {named!r}; the design's are "
                             f"{list(bodies)}")
        if 'local' in variable:
            local = variable['local']
            if not isinstance(local, dict) or set(local) - LOCAL_KEYS or len(named) != 1 or \
                    any(k in variable for k in ('translate', 'rotate', 'scale')):
                raise ValueError(f"{design_path}: variable {variable['name']!r}: 'local' takes {sorted(LOCAL_KEYS)} and acts on "
                                 f"one body (its 'handles'), without translate/rotate/scale; not {variable!r}")
            dvs.addLocalDV(variable['name'], regions[named[0]], lower=variable.get('lower'), upper=variable.get('upper'),
                           value=variable.get('value', 0.0), **local)
            continue
        axes = {k: variable[k] for k in ('translate', 'rotate', 'scale') if k in variable}
        dvs.addHandleDV(variable['name'], [regions[b] for b in named], lower=variable.get('lower'), upper=variable.get('upper'),
                        value=variable.get('value', 0.0), **axes)
    return dvs


def main(argv):
    from . import designOfExperiments
    from .experiments import _fem
    parser = argparse.ArgumentParser(prog='mlsdeform-doe.py', description='Design of experiments on an OpenFOAM case or an FEM deck.')
    parser.add_argument('design', help='the design file (JSON): case or deck, patches or sets by role, variables')
    parser.add_argument('folder', help='where the variants and report.csv go')
    choice = parser.add_mutually_exclusive_group(required=True)
    choice.add_argument('--samples', type=int, help='a Latin hypercube of this many variants in the bounds')
    choice.add_argument('--table', help='a CSV table of values: one column per variable, one row per variant')
    parser.add_argument('--seed', type=int, default=0, help="the Latin hypercube's seed (default 0)")
    parser.add_argument('--write-failed', action='store_true', help='write the variants that fail the thresholds too')
    parser.add_argument('--copy', action='store_true', help="self-contained variants (default: links to the source's unchanged files)")
    parser.add_argument('--max-non-orthogonality', type=float, default=70.0, help='degrees (default 70)')
    parser.add_argument('--max-skewness', type=float, default=4.0, help='default 4')
    parser.add_argument('--max-inverted-cells', type=int, default=0, help='default 0')
    parser.add_argument('--min-scaled-jacobian', type=float, default=0.1, help="a deck's elements' (default 0.1)")
    arguments = parser.parse_args(argv)
    try:
        dvs = setUp(arguments.design)
        thresholds = {'InvertedCells': arguments.max_inverted_cells}
        thresholds.update({'MinScaledJacobian': arguments.min_scaled_jacobian} if _fem(dvs) else
                          {'MaxNonOrthogonality': arguments.max_non_orthogonality, 'MaxSkewness': arguments.max_skewness})
        rows = designOfExperiments(dvs, arguments.folder, samples=arguments.samples, seed=arguments.seed, table=arguments.table,
                                   thresholds=thresholds, writeFailed=arguments.write_failed, copy=arguments.copy)
    except (ValueError, OSError, json.JSONDecodeError) as e:
        print(f"mlsdeform-doe: {e}", file=sys.stderr)
        return 2
    except RuntimeError as e:
        print(f"mlsdeform-doe: {e}", file=sys.stderr)
        return 1
    passed = sum(1 for r in rows if r['ok'])
    print(f"{len(rows)} variants, {passed} pass the thresholds; report: {os.path.join(os.path.abspath(arguments.folder), 'report.csv')}")
    return 0
