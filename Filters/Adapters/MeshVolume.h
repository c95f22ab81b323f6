// The volume of a volume mesh's 3D cells and its exact gradient at the mesh's points, as the mesh's
// solver measures it: an FEM mesh's linear and quadratic tetrahedra, hexahedra and wedges as
// CalculiX integrates the isoparametric element (Structural/ShapeSensitivity.h meshVolume: a deck's
// mass is its density times this); a CFD mesh's cells (and an FEM mesh's other cells) as OpenFOAM
// does, by pyramids on their faces (Quality/FaceQuality.h cellGeometry), whose sum over a set of
// cells is sum_f S_f . C_f / 3 over the faces that bound the set (the divergence theorem: the cell
// centres drop out, sum_f S_f = 0 over a closed cell), so that only the set's boundary has a
// gradient. For design constraints on a part's volume or mass (DesignConstraints.addMeshVolumeConstraint).
#pragma once

#include "Common/CoreTypes.h"
#include "Quality/PolygonSurface.h"
#include "Structural/ShapeSensitivity.h"

#include <vector>

class vtkUnstructuredGrid;

namespace mlsvtk
{
class MeshVolume
{
public:
  /// The grid's 3D cells with selected[cell] set (empty: every one), found on its rest points:
  /// for an FEM mesh (fem) its isoparametric elements, and for the other cells the faces that
  /// bound their union (a face that one of them alone has), each oriented out of its cell. Its
  /// points are offset .. offset + n - 1 of the point lists volume() gets (several grids' points).
  MeshVolume(vtkUnstructuredGrid* grid, const mlsdeform::PointList& rest, const std::vector<char>& selected, bool fem, int offset);

  /// The number of cells measured.
  long cells() const { return Cells; }

  /// The volume on points (the grids', deformed), and when rows is given dV/dX at the points
  /// that have one (the elements' nodes, the bounding faces' points: rows ascending, gradient a
  /// value each). The elements and faces are summed in parallel, each point's terms in element
  /// and face order: the same bits for any thread count.
  double volume(const mlsdeform::PointList& points, std::vector<int>* rows, mlsdeform::PointList* gradient) const;

private:
  mlsdeform::SolidMesh Elements;
  mlsdeform::PolygonSurface Faces{ { 0 }, {} }; // the bounding faces, each oriented out of its cell
  long Cells = 0;
};
} // namespace mlsvtk
