"""A CGNS file as a solver's pre-processor writes it, for the tests of Save Data's variant: an
unstructured zone of 3x3x3 hexahedra (nodes 0-3 on each axis) with its boundary faces as three
element sections and three element-range BCs (bottom z = 0, top z = 3, sides), each BC in a
family of its own (wall, lid, farfield), and a flow solution of pressures at the vertices.
Written with Debian's CGNS 3.4 (cgns-convert: aflr3_to_cgns, then the library itself through
ctypes for the families and the solution), so that the CGNS project's own cgnscheck and cgnsdiff,
of the same version, read the file and its variants.

    make(path) -> path
"""
import ctypes
import os
import subprocess

N = 4  # nodes along an axis
FAMILIES = ('wall', 'lid', 'farfield')  # the BCs' families, in the BCs' order (their tags 1, 2, 3)


def _ugrid(path):
    """The mesh in AFLR3's ASCII ugrid format: nodes, boundary quads with their tags, hexahedra."""
    def node(i, j, k):
        return 1 + i + N * (j + N * k)
    m = N - 1
    quads = []
    for a in range(m):
        for b in range(m):
            quads += [((node(a, b, 0), node(a, b + 1, 0), node(a + 1, b + 1, 0), node(a + 1, b, 0)), 1),
                      ((node(a, b, m), node(a + 1, b, m), node(a + 1, b + 1, m), node(a, b + 1, m)), 2),
                      ((node(0, a, b), node(0, a, b + 1), node(0, a + 1, b + 1), node(0, a + 1, b)), 3),
                      ((node(m, a, b), node(m, a + 1, b), node(m, a + 1, b + 1), node(m, a, b + 1)), 3),
                      ((node(a, 0, b), node(a + 1, 0, b), node(a + 1, 0, b + 1), node(a, 0, b + 1)), 3),
                      ((node(a, m, b), node(a, m, b + 1), node(a + 1, m, b + 1), node(a + 1, m, b)), 3)]
    hexes = [(node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
              node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1))
             for k in range(m) for j in range(m) for i in range(m)]
    with open(path, 'w') as f:
        f.write('%d 0 %d 0 0 0 %d\n' % (N ** 3, len(quads), len(hexes)))
        f.writelines('%d %d %d\n' % (i, j, k) for k in range(N) for j in range(N) for i in range(N))
        f.writelines('%d %d %d %d\n' % q for q, _ in quads)
        f.writelines('%d\n' % tag for _, tag in quads)
        f.writelines(' '.join(map(str, h)) + '\n' for h in hexes)


def make(path):
    ugrid = os.path.splitext(path)[0] + '.ugrid'
    _ugrid(ugrid)
    subprocess.run(['aflr3_to_cgns', '-f', ugrid, path], check=True, stdout=subprocess.DEVNULL)
    os.remove(ugrid)
    cg = ctypes.CDLL('libcgns.so.3.4')
    fn, index = ctypes.c_int(), ctypes.c_int()

    def ok(status, what):
        if status != 0:
            raise RuntimeError('CGNS 3.4: %s failed: %s' % (what, ctypes.c_char_p(cg.cg_get_error()).value.decode()))

    cg.cg_get_error.restype = ctypes.c_void_p
    ok(cg.cg_open(path.encode(), 2, ctypes.byref(fn)), 'cg_open')  # CG_MODE_MODIFY
    for bc, family in enumerate(FAMILIES, start=1):
        ok(cg.cg_family_write(fn, 1, family.encode(), ctypes.byref(index)), 'cg_family_write')
        ok(cg.cg_goto(fn, 1, b'Zone_t', 1, b'ZoneBC_t', 1, b'BC_t', bc, b'end'), 'cg_goto')
        ok(cg.cg_famname_write(family.encode()), 'cg_famname_write')
    ok(cg.cg_sol_write(fn, 1, 1, b'Solution', 2, ctypes.byref(index)), 'cg_sol_write')  # Vertex
    pressure = (ctypes.c_double * N ** 3)(*[1.5 * n for n in range(N ** 3)])
    field = ctypes.c_int()
    ok(cg.cg_field_write(fn, 1, 1, index, 4, b'Pressure', pressure, ctypes.byref(field)), 'cg_field_write')  # RealDouble
    ok(cg.cg_close(fn), 'cg_close')
    return path
