// VTK cells as the core's simplices: the surface triangles and volume tetrahedra of point sets
// (the domain to sample), split by their vertices' positions, and cheap per-type cell access.
#pragma once

#include "Common/Collective.h"
#include "Common/SamplingDomain.h"
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>
#include <vtkUnstructuredGrid.h>
#include <vector>

class vtkDataSet;
class vtkGenericCell;
class vtkPointSet;

namespace mlsvtk
{
/// Surface triangles and volume tetrahedra of the point sets (indices into points(sets)); ghost
/// cells (another process's) are left out. When there are 3D cells but no 2D cells (on all
/// processes of group), the boundary faces of the 3D cells are the surface, without the faces
/// that pieces on different processes share.
mlsdeform::SamplingDomain samplingDomain(const std::vector<vtkPointSet*>& sets, const mlsdeform::Collective& group = mlsdeform::serial());

/// A volume set's boundary faces as polygons (vtkGeometryFilter: each face as its cell lists it,
/// its normal out of the mesh), without the faces that pieces on different processes share;
/// originalIds maps their points to the set's (nullptr: the set's own ids). Null faces for a set
/// that is not an unstructured grid.
struct BoundaryFaces
{
  vtkSmartPointer<vtkPolyData> faces;
  const vtkIdType* originalIds = nullptr;
};
std::vector<BoundaryFaces> boundaryFaces(const std::vector<vtkPointSet*>& sets, const mlsdeform::Collective& group);

/// The dimension of a VTK cell type (0 for an unknown type). vtkCellTypes::GetDimension builds a
/// cell of the type on every call (for a snappyHexMesh cell, a polyhedron object); this asks it
/// once per type.
int cellDimension(int type);

/// Calls visit(points, n) for every face of a polyhedron cell as its face stream stores it (no
/// vtkPolyhedron object, whose construction costs more than what is done with it).
template <typename Visit>
void visitPolyhedronFaces(vtkUnstructuredGrid* grid, vtkIdType cell, Visit visit)
{
  vtkIdType faces = 0;
  const vtkIdType* stream = nullptr;
  grid->GetFaceStream(cell, faces, stream);
  for (vtkIdType f = 0; f < faces && stream; ++f)
  {
    const vtkIdType n = *stream++;
    visit(stream, n);
    stream += n;
  }
}

/// A cell of a dataset in a vtkGenericCell kept per cell type: one vtkGenericCell rebuilds its
/// cell whenever the type changes, and a polyhedron's rebuild costs more than what is done with it.
class CellsByType
{
public:
  vtkGenericCell* get(vtkDataSet* set, vtkIdType cell);

private:
  std::vector<vtkSmartPointer<vtkGenericCell>> Cells;
};
} // namespace mlsvtk
