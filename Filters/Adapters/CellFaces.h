// The faces of VTK's 3D cell types, as polygons of positions in a cell's point list: one table for
// the sampling domain (MeshCells) and the face-based quality (VolumeMeshQuality).
#pragma once

#include <vector>

namespace mlsvtk
{
/// A cell type's faces, each a list of positions in the point list of any cell of the type.
using LocalFaces = std::vector<std::vector<int>>;

/// The faces of a 3D cell type in VTK's order (vtkCell::GetFace), each listed around the face
/// (counter-clockwise seen from outside) as VTK lists them, but for the voxel's: VTK gives them as
/// pixels, whose points are in raster order (a polygon of them crosses itself), and here they come
/// around the face like the hexahedron's. A quadratic type's faces list the corners around the face,
/// then the edge (and face) nodes, as VTK does. Empty for other types: the polyhedron (faces per
/// cell: visitPolyhedronFaces), the convex point set (faces from the points' positions), the
/// higher-order (Lagrange, Bezier) types, and cells of other dimensions. Asked of VTK once; safe to
/// call from several threads.
const LocalFaces& cellTypeFaces(int type);
} // namespace mlsvtk
