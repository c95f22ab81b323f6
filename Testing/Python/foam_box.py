"""A blockMesh box as an OpenFOAM case folder, for the tests that need a small case of known
geometry (one hexahedral block, its eight corners given: a box or a parallelepiped)."""
import os
import subprocess

FOAM = 'source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1; set -e; '
HEADER = 'FoamFile { version 2.0; format ascii; class dictionary; object %s; }\n'
CONTROL = HEADER % 'controlDict' + 'application icoFoam; startFrom startTime; startTime 0; stopAt endTime; endTime 1; deltaT 1;\n' \
    'writeControl timeStep; writeInterval 1; writeFormat ascii; writePrecision 17;\n'
SCHEMES = HEADER % 'fvSchemes' + 'ddtSchemes { default Euler; } gradSchemes { default Gauss linear; } divSchemes { default none; } ' \
    'laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; } snGradSchemes { default corrected; }\n'
SOLUTION = HEADER % 'fvSolution' + 'solvers { }\n'
BOX = ((0, 0, 0), (2, 0, 0), (2, 1, 0), (0, 1, 0), (0, 0, 1), (2, 0, 1), (2, 1, 1), (0, 1, 1))


def box_case(case, corners=BOX, cells=(8, 4, 4)):
    """Writes the case folder (system/ and case.foam) of one block with these corners (blockMesh's
    order) and cells, patches lid (top), base (bottom) and sides, and runs blockMesh there."""
    blocks = HEADER % 'blockMeshDict' + '''convertToMeters 1;
vertices (%s);
blocks (hex (0 1 2 3 4 5 6 7) (%d %d %d) simpleGrading (1 1 1));
boundary
(
    lid { type wall; faces ((4 5 6 7)); }
    base { type wall; faces ((0 3 2 1)); }
    sides { type patch; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2)); }
);
''' % (' '.join('(%r %r %r)' % tuple(c) for c in corners), *cells)
    os.makedirs(os.path.join(case, 'system'), exist_ok=True)
    for name, text in (('controlDict', CONTROL), ('blockMeshDict', blocks), ('fvSchemes', SCHEMES), ('fvSolution', SOLUTION)):
        with open(os.path.join(case, 'system', name), 'w') as f:
            f.write(text)
    open(os.path.join(case, 'case.foam'), 'w').close()
    subprocess.run(['bash', '-c', FOAM + 'cd "%s" && blockMesh > log.blockMesh' % case], check=True)
