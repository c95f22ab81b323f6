// Conversion of VTK inputs (a vtkPointSet or a composite of point sets) into the core's types:
// the leaves in traversal order, their points concatenated, and the domain to sample (2D cells as
// the surface, 3D cells as the volume). Not wrapped; used by the MLS filters.
#pragma once

#include "SpaceDeformation.h"

#include <vtkSmartPointer.h>
#include <vtkType.h>
#include <vtkUnstructuredGrid.h>

#include <string>
#include <vector>

class vtkDataObject;
class vtkDataSet;
class vtkGenericCell;
class vtkObject;
class vtkPointSet;
class vtkPolyData;

namespace mlsgeometry
{
/// The point sets in a vtkPointSet or composite dataset, in traversal order. Other leaf types
/// (image data, ...) are skipped and counted in skipped.
std::vector<vtkPointSet*> pointSets(vtkDataObject* input, int* skipped = nullptr);

/// All points of the point sets, concatenated.
mlsdeform::PointList points(const std::vector<vtkPointSet*>& sets);

/// Surface triangles and volume tetrahedra of the point sets (indices into points(sets)); ghost
/// cells (another process's) are left out. When there are 3D cells but no 2D cells (on all
/// processes of group), the boundary faces of the 3D cells are the surface, without the faces
/// that pieces on different processes share.
mlsdeform::SamplingDomain samplingDomain(const std::vector<vtkPointSet*>& sets, const mlsdeform::Collective& group = mlsdeform::serial());

/// The dimension of a VTK cell type (0 for an unknown type). vtkCellTypes::GetDimension builds a
/// cell of the type on every call (for a snappyHexMesh cell, a polyhedron object); this asks it
/// once per type.
int cellDimension(int type);

/// Makes cell a cell of the type whose point ids are 0 .. n-1, so that what VTK derives from it (its
/// faces, its simplices) comes as positions in the point list of any cell of that type: asked once
/// per type and mapped through each cell's point ids, instead of a vtkGenericCell per cell.
void setLocalCell(vtkGenericCell* cell, int type);

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

/// Identifies versions of VTK data by VTK's own change tracking: the objects and their
/// modification times. A modification gives an object a newer MTime than any before it, and a
/// new object starts newer than all existing ones, so equal stamps mean unmodified data.
struct Stamp
{
  std::vector<std::pair<const void*, vtkMTimeType>> objects;
  void add(vtkObject* object);
  bool operator==(const Stamp& other) const { return objects == other.objects; }
  bool operator!=(const Stamp& other) const { return !(*this == other); }
};

/// What a deformation's subspace (shape functions and energies) depends on besides the input's
/// point coordinates and cells: property values, compared exactly, and the stamps of further
/// inputs (external samples); and whether it depends on the input's points and cells (internal
/// sampling, energies on the input's mesh). It is rebuilt when any of them changes.
struct SubspaceDependencies
{
  std::vector<double> settings;
  Stamp inputs;
  bool geometry = true;
  bool operator==(const SubspaceDependencies& other) const
  {
    return settings == other.settings && inputs == other.inputs && geometry == other.geometry;
  }
};

/// The stamp of the point coordinates of the sets.
Stamp pointsStamp(const std::vector<vtkPointSet*>& sets);

/// The stamp of the cells (connectivity and types) of the sets.
Stamp cellsStamp(const std::vector<vtkPointSet*>& sets);

/// Points (with vertices) carrying the given point arrays, one value per point.
vtkSmartPointer<vtkPolyData> pointCloud(const mlsdeform::PointList& points,
  const std::vector<std::pair<std::string, const std::vector<double>*>>& arrays);

/// Reports progress of the core to a VTK algorithm (client is a vtkAlgorithm*).
void reportProgress(void* algorithm, double fraction);
}
