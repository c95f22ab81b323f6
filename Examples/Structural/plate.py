"""A plate with holes for the structural design loop: meshed by Gmsh into quadratic tetrahedra
(C3D10), written as a CalculiX deck whose mesh is an included file, and run with ccx.

mesh_plate(folder, ...) writes folder/mesh.inp: the nodes, the C3D10 elements and the sets a user
names regions by (node sets fixed, load, tip: the loaded end away from the fillets, hole1, hole2,
..., fillet, the plane faces bottom, top, front and back, surface: every boundary node, and the
element set part), without the boundary triangles Gmsh adds for the surface groups (ccx
would take them for plane-stress elements). write_analysis(folder) writes folder/plate.inp: steel,
the fixed end clamped, a load on the far end, a static step, and, with responses, the sensitivity
step whose derivatives mlsdeform.readCalculixSensitivity reads (the exact path,
mlsdeform.exactSensitivity, needs no sensitivity step). run_ccx(deck) runs ccx on a deck in
its folder and returns what it printed for the load nodes (the displacements, from the .dat file).
"""
import os
import re
import subprocess

GEO = '''SetFactory("OpenCASCADE");
{solid}
e = 1e-6 * {length};
{fillet}
Physical Volume("part") = Volume{{:}};
Physical Surface("fixed") = Surface In BoundingBox{{-e, -e, -e, e, {width} + e, {thickness} + e}};
Physical Surface("load") = Surface In BoundingBox{{{length} - e, -e, -e, {length} + e, {width} + e, {thickness} + e}};
{hole_groups}
Physical Surface("bottom") = Surface In BoundingBox{{-e, -e, -e, {length} + e, {width} + e, e}};
Physical Surface("top") = Surface In BoundingBox{{-e, -e, {thickness} - e, {length} + e, {width} + e, {thickness} + e}};
Physical Surface("front") = Surface In BoundingBox{{-e, -e, -e, {length} + e, e, {thickness} + e}};
Physical Surface("back") = Surface In BoundingBox{{-e, {width} - e, -e, {length} + e, {width} + e, {thickness} + e}};
Physical Surface("surface") = Surface{{:}};
Mesh.ElementOrder = 2;
Mesh.CharacteristicLengthMax = {size};
Mesh.SaveGroupsOfNodes = 1;
'''

# The solid: the box minus the holes' cylinders (meshed freely), or the section (the rectangle
# minus the holes' disks) extruded through the thickness in layers.
SOLID = '''Box(1) = {{0, 0, 0, {length}, {width}, {thickness}}};
{cylinders}
BooleanDifference(100) = {{ Volume{{1}}; Delete; }}{{ {tools} }};'''
EXTRUDED = '''Rectangle(1) = {{0, 0, 0, {length}, {width}}};
{disks}
section() = BooleanDifference{{ Surface{{1}}; Delete; }}{{ {tools} }};
Extrude {{0, 0, {thickness}}} {{ Surface{{section()}}; Layers{{{layers}}}; }}'''

# Steel in mm, N, MPa (t/mm^3 for the density).
DENSITY = 7.85e-9
ANALYSIS = '''*HEADING
Plate with holes: clamped at x = 0, loaded at x = {length}
*INCLUDE, INPUT=mesh.inp
*MATERIAL, NAME=STEEL
*ELASTIC
210000., 0.3
*DENSITY
{density}
*SOLID SECTION, ELSET=part, MATERIAL=STEEL
{design}*STEP
*STATIC
*BOUNDARY
fixed, 1, 3
*CLOAD
{loads}
*NODE FILE{precision}
U
*NODE PRINT, NSET=load
U
*END STEP
{sensitivity}'''

# The sensitivity step (ccx 2.20): after the static step, one *DESIGNRESPONSE card a response.
SENSITIVITY = '''*STEP
*SENSITIVITY, WRITE
{responses}*END STEP
'''


def mesh_plate(folder, holes=((5.0, 2.0, 1.0),), length=10.0, width=4.0, thickness=1.0, size=0.6, fillet=0.0,
               layers=0, gmsh='gmsh'):
    """Meshes the plate minus the holes (x, y, radius), its two corners at the loaded end rounded by
    a fillet of that radius (0: none; the set fillet), into folder/mesh.inp; returns its path.
    layers: 0, the solid meshed freely; n, its section meshed and extruded through the thickness
    in n layers of tetrahedra, so that every node lies on a line across the plate (local variables
    with a line axis then hold the hole's outline through the whole thickness); without fillet."""
    if layers and fillet > 0:
        raise ValueError('an extruded plate (layers) has no fillet')
    os.makedirs(folder, exist_ok=True)
    if layers:
        solid = EXTRUDED.format(length=length, width=width, thickness=thickness, layers=int(layers), tools='Surface{%s}; Delete;' % (
            ', '.join(str(2 + i) for i in range(len(holes)))), disks='\n'.join(
            f'Disk({2 + i}) = {{{x}, {y}, 0, {r}}};' for i, (x, y, r) in enumerate(holes)))
    else:
        solid = SOLID.format(length=length, width=width, thickness=thickness, tools='Volume{%s}; Delete;' % (
            ', '.join(str(2 + i) for i in range(len(holes)))), cylinders='\n'.join(
            f'Cylinder({2 + i}) = {{{x}, {y}, -1, 0, 0, {thickness + 2}, {r}}};' for i, (x, y, r) in enumerate(holes)))
    groups = '\n'.join(f'Physical Surface("hole{i + 1}") = Surface In BoundingBox{{{x - r} - e, {y - r} - e, -e, '
                       f'{x + r} + e, {y + r} + e, {thickness} + e}};' for i, (x, y, r) in enumerate(holes))
    geo = os.path.join(folder, 'plate.geo')
    with open(geo, 'w') as f:
        rounded = ''
        if fillet > 0:
            # the edges along z at (length, 0) and (length, width), rounded
            rounded = (f'edges() = Curve In BoundingBox{{{length} - e, -e, -e, {length} + e, e, {thickness} + e}};\n'
                       f'edges() += Curve In BoundingBox{{{length} - e, {width} - e, -e, {length} + e, {width} + e, {thickness} + e}};\n'
                       f'Fillet{{100}}{{edges()}}{{{fillet}}}\n')
            groups += (f'\nPhysical Surface("fillet") = Surface In BoundingBox{{{length - fillet} - e, -e, -e, {length} + e, '
                       f'{fillet} + e, {thickness} + e}};\n'
                       f'Physical Surface("fillet") += Surface In BoundingBox{{{length - fillet} - e, {width - fillet} - e, -e, '
                       f'{length} + e, {width} + e, {thickness} + e}};')
        f.write(GEO.format(length=length, width=width, thickness=thickness, solid=solid, hole_groups=groups, size=size,
                           fillet=rounded))
    raw = os.path.join(folder, 'gmsh.inp')
    subprocess.run([gmsh, '-3', geo, '-o', raw, '-format', 'inp'], check=True, stdout=subprocess.DEVNULL)
    mesh = os.path.join(folder, 'mesh.inp')
    with open(raw) as f, open(mesh, 'w') as out:
        out.write(volume_elements_only(f.read()))
    os.remove(raw)
    # tip: the middle of the loaded end, well away from its fillets (the fillets' motion shears the
    # end between them and the tip), where the displacement response is measured
    margin = fillet + 0.25 * width
    coordinates = node_coordinates(mesh)
    tip = [n for n in node_set(mesh, 'load') if margin <= coordinates[n][1] <= width - margin]
    with open(mesh, 'a') as out:
        out.write('*NSET, NSET=tip\n' + ''.join(f'{n},\n' for n in tip))
    return mesh


def node_coordinates(deck):
    """{node: (x, y, z)} of a deck's *NODE lines (one data line a node)."""
    nodes, inside = {}, False
    with open(deck) as f:
        for line in f:
            if line.startswith('*'):
                inside = re.match(r'\*NODE\s*(,|$)', line.strip(), re.I) is not None
            elif inside and line.strip():
                values = line.split(',')
                nodes[int(values[0])] = tuple(float(v) for v in values[1:4])
    return nodes


def volume_elements_only(deck):
    """The deck without its heading (the analysis deck has its own: ccx allows one), its 2D
    elements (Gmsh's CPS/S/T boundary elements) and the element sets that held only those."""
    blocks = re.split(r'(?m)^(?=\*)', deck)
    dropped = set()
    for block in blocks:
        header = block.split('\n', 1)[0].upper().replace(' ', '')
        if header.startswith('*ELEMENT,') and not re.search(r'TYPE=C3D', header):
            dropped.update(int(line.split(',')[0]) for line in block.split('\n')[1:] if line.strip())
    kept = []
    for block in blocks:
        header = block.split('\n', 1)[0].upper().replace(' ', '')
        lines = [line for line in block.split('\n')[1:] if line.strip()]
        if header.startswith('*HEADING') or header.startswith('*ELEMENT,') and not re.search(r'TYPE=C3D', header):
            continue
        if header.startswith('*ELSET,'):
            ids = {int(v) for line in lines for v in line.split(',') if v.strip()}
            if ids <= dropped:
                continue
        kept.append(block)
    text = ''.join(kept)
    return text if text.endswith('\n') else text + '\n'


def write_analysis(folder, length=10.0, force=-100.0, responses=(), double=False, dof=3):
    """folder/plate.inp: the static analysis of folder/mesh.inp, force (N, along the axis dof: 1 x,
    2 y, 3 z) spread evenly over the load nodes; responses: (name, definition) pairs of a sensitivity step on the surface nodes,
    e.g. (('MASS', 'MASS'), ('TIP', 'ALL-DISP, tip')): the tip displacement's norm over the tip
    nodes, which the morph keeps fixed (a displacement response over nodes it moves would measure
    the mesh, not the part). double: the displacements in full precision (*NODE FILE, DOUBLE: a
    binary .frd, which the exact gradient reads and ccx's own sensitivity path cannot)."""
    load = node_set(os.path.join(folder, 'mesh.inp'), 'load')
    loads = '\n'.join(f'{n}, {dof}, {force / len(load):.9g}' for n in load)
    design = '*DESIGNVARIABLES, TYPE=COORDINATE\nsurface\n' if responses else ''
    cards = ''.join(f'*DESIGNRESPONSE, NAME={name}\n{definition}\n' for name, definition in responses)
    deck = os.path.join(folder, 'plate.inp')
    with open(deck, 'w') as f:
        f.write(ANALYSIS.format(length=length, density=DENSITY, loads=loads, design=design, precision=', DOUBLE' if double else '',
                                sensitivity=SENSITIVITY.format(responses=cards) if responses else ''))
    return deck


def node_set(deck, name):
    """The node ids of the *NSET name of a (Gmsh-written) deck."""
    ids, inside = [], False
    with open(deck) as f:
        for line in f:
            if line.startswith('*'):
                inside = re.match(r'\*NSET\s*,\s*NSET\s*=\s*' + re.escape(name) + r'\s*$', line.strip(), re.I) is not None
            elif inside:
                ids += [int(v) for v in line.split(',') if v.strip()]
    return ids


def run_ccx(deck, ccx='ccx', threads=1):
    """Runs ccx on deck in its folder; returns {node: (ux, uy, uz)} of the printed displacements."""
    folder, name = os.path.split(os.path.abspath(deck))
    job = os.path.splitext(name)[0]
    result = subprocess.run([ccx, '-i', job], cwd=folder, capture_output=True, text=True,
                            env=dict(os.environ, OMP_NUM_THREADS=str(threads)))
    log = result.stdout + result.stderr
    if result.returncode != 0 or '*ERROR' in log:
        raise RuntimeError(f'ccx failed on {deck}:\n' + log[-2000:])
    stiffness = os.path.join(folder, job + '.stm')  # the static step's stiffness dump for the sensitivity step
    if os.path.exists(stiffness):
        os.remove(stiffness)
    displacements = {}
    with open(os.path.join(folder, job + '.dat')) as f:
        for line in f:
            values = line.split()
            if len(values) == 4 and values[0].isdigit():
                displacements[int(values[0])] = tuple(float(v) for v in values[1:])
    return displacements
