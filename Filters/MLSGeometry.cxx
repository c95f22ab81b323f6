#include "MLSGeometry.h"

#include "PositionHash.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <vtkAlgorithm.h>
#include <vtkCell.h>
#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkCompositeDataIterator.h>
#include <vtkDataSetAttributes.h>
#include <vtkUnsignedCharArray.h>
#include <vtkCompositeDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkGenericCell.h>
#include <vtkGeometryFilter.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>


namespace mlsgeometry
{
std::vector<vtkPointSet*> pointSets(vtkDataObject* input, int* skipped)
{
  std::vector<vtkPointSet*> sets;
  int others = 0;
  if (auto* set = vtkPointSet::SafeDownCast(input))
  {
    sets.push_back(set);
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it = vtkSmartPointer<vtkCompositeDataIterator>::Take(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (auto* leaf = vtkPointSet::SafeDownCast(it->GetCurrentDataObject()))
      {
        sets.push_back(leaf);
      }
      else
      {
        ++others;
      }
    }
  }
  else if (input)
  {
    ++others;
  }
  if (skipped)
  {
    *skipped = others;
  }
  return sets;
}

namespace
{
// Copies the coordinates of a float or double array (false for other types).
template <typename Array>
bool copyCoordinates(vtkDataArray* data, mlsdeform::Vec3* out)
{
  auto* array = Array::SafeDownCast(data);
  if (!array)
  {
    return false;
  }
  const auto* in = array->GetPointer(0);
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    out[i] = mlsdeform::Vec3(in[3 * i], in[3 * i + 1], in[3 * i + 2]);
  }
  return true;
}
}

mlsdeform::PointList points(const std::vector<vtkPointSet*>& sets)
{
  mlsdeform::PointList out;
  for (vtkPointSet* set : sets)
  {
    const vtkIdType n = set->GetNumberOfPoints();
    const std::size_t offset = out.size();
    out.resize(offset + n);
    vtkDataArray* data = n > 0 ? set->GetPoints()->GetData() : nullptr;
    if (n > 0 && !copyCoordinates<vtkFloatArray>(data, &out[offset]) && !copyCoordinates<vtkDoubleArray>(data, &out[offset]))
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        set->GetPoint(i, out[offset + i].data());
      }
    }
  }
  return out;
}

namespace
{
// The tetrahedra of a polyhedron, star-shaped about its first point (OpenFOAM's cells are):
// that point joined to a fan of triangles of every face that does not hold it. VTK's
// vtkPolyhedron::Triangulate builds a Delaunay tetrahedralization and a polyhedron object per
// cell, most of the sampling's time on a snappyHexMesh mesh.
template <typename Add>
void polyhedronTetrahedra(vtkUnstructuredGrid* grid, vtkIdType cell, Add add)
{
  vtkIdType apex = -1;
  visitPolyhedronFaces(grid, cell, [&](const vtkIdType* face, vtkIdType n) {
    apex = apex < 0 && n > 0 ? face[0] : apex;
    if (std::find(face, face + n, apex) != face + n)
    {
      return;
    }
    for (vtkIdType v = 1; v + 1 < n; ++v)
    {
      add({ apex, face[0], face[v], face[v + 1] });
    }
  });
}

// The simplices VTK splits a cell of a type with a fixed triangulation into (its Triangulate
// with index 0), as positions in the cell's point list (setLocalCell); empty for other types (a
// pyramid's or a quad's split depends on its shape). A vtkGenericCell per cell took most of the
// sampling domain's time on a 1M-cell mesh.
const std::vector<vtkIdType>& fixedSimplices(int type)
{
  static const std::array<std::vector<vtkIdType>, VTK_NUMBER_OF_CELL_TYPES> simplices = [] {
    std::array<std::vector<vtkIdType>, VTK_NUMBER_OF_CELL_TYPES> out;
    vtkNew<vtkGenericCell> cell;
    vtkNew<vtkIdList> ids;
    vtkNew<vtkPoints> pts;
    for (int fixed : { VTK_HEXAHEDRON, VTK_VOXEL, VTK_WEDGE })
    {
      setLocalCell(cell, fixed);
      if (cell->Triangulate(0, ids, pts))
      {
        out[fixed].assign(ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfIds());
      }
    }
    return out;
  }();
  return type >= 0 && type < VTK_NUMBER_OF_CELL_TYPES ? simplices[type] : simplices[VTK_EMPTY_CELL];
}

// Splits every cell of the given dimension into simplices (triangles or tetrahedra): simplices
// are taken as they are, polygons become fans, polyhedra tetrahedra about a point, other cells
// of a fixed topology by their type's simplices, others are triangulated by VTK.
template <std::size_t N>
void simplices(vtkDataSet* set, int dimension, const vtkIdType* pointMap, int offset, std::vector<std::array<int, N>>& out)
{
  const int simplexType = N == 3 ? VTK_TRIANGLE : VTK_TETRA;
  CellsByType cells;
  vtkNew<vtkIdList> ids;
  vtkNew<vtkPoints> pts;
  auto addIds = [&](const std::array<vtkIdType, N>& simplex) {
    std::array<int, N> mapped;
    for (std::size_t v = 0; v < N; ++v)
    {
      mapped[v] = offset + static_cast<int>(pointMap ? pointMap[simplex[v]] : simplex[v]);
    }
    out.push_back(mapped);
  };
  auto add = [&](vtkIdType first) {
    std::array<vtkIdType, N> simplex;
    for (std::size_t v = 0; v < N; ++v)
    {
      simplex[v] = ids->GetId(first + static_cast<vtkIdType>(v));
    }
    addIds(simplex);
  };
  auto* grid = vtkUnstructuredGrid::SafeDownCast(set);
  vtkUnsignedCharArray* ghosts = set->GetCellGhostArray();
  for (vtkIdType c = 0; c < set->GetNumberOfCells(); ++c)
  {
    if (ghosts && (ghosts->GetValue(c) & vtkDataSetAttributes::DUPLICATECELL))
    {
      continue; // another process's cell, sampled there
    }
    const int type = set->GetCellType(c);
    if (type == simplexType)
    {
      set->GetCellPoints(c, ids);
      add(0);
      continue;
    }
    if (cellDimension(type) != dimension)
    {
      continue;
    }
    if constexpr (N == 3)
    {
      if (type == VTK_POLYGON || type == VTK_QUAD)
      {
        set->GetCellPoints(c, ids);
        for (vtkIdType v = 1; v + 1 < ids->GetNumberOfIds(); ++v)
        {
          addIds({ ids->GetId(0), ids->GetId(v), ids->GetId(v + 1) });
        }
        continue;
      }
    }
    else
    {
      if (type == VTK_POLYHEDRON && grid)
      {
        polyhedronTetrahedra(grid, c, addIds);
        continue;
      }
    }
    if (const std::vector<vtkIdType>& local = fixedSimplices(type); !local.empty() && grid)
    {
      // a cell of fixed topology: its type's simplices mapped through its point ids
      vtkIdType n = 0;
      const vtkIdType* cellPoints = nullptr;
      grid->GetCellPoints(c, n, cellPoints);
      ids->SetNumberOfIds(static_cast<vtkIdType>(local.size()));
      for (std::size_t v = 0; v < local.size(); ++v)
      {
        ids->SetId(static_cast<vtkIdType>(v), cellPoints[local[v]]);
      }
    }
    else if (!cells.get(set, c)->Triangulate(0, ids, pts))
    {
      continue;
    }
    for (vtkIdType s = 0; s + static_cast<vtkIdType>(N) <= ids->GetNumberOfIds(); s += N)
    {
      add(s);
    }
  }
}
}

void setLocalCell(vtkGenericCell* cell, int type)
{
  cell->SetCellType(type);
  for (vtkIdType i = 0; i < cell->GetPointIds()->GetNumberOfIds(); ++i)
  {
    cell->GetPointIds()->SetId(i, i);
  }
}

int cellDimension(int type)
{
  // the dimension plus one, 0 until asked (static storage starts at zero); concurrent first
  // calls store the same value
  static std::array<std::atomic<int>, VTK_NUMBER_OF_CELL_TYPES> known;
  if (type < 0 || type >= VTK_NUMBER_OF_CELL_TYPES)
  {
    return 0;
  }
  if (known[type] == 0)
  {
    known[type] = 1 + vtkCellTypes::GetDimension(static_cast<unsigned char>(type));
  }
  return known[type] - 1;
}

mlsdeform::SamplingDomain samplingDomain(const std::vector<vtkPointSet*>& sets, const mlsdeform::Collective& group)
{
  mlsdeform::SamplingDomain domain;
  domain.points = points(sets);
  int offset = 0;
  for (vtkPointSet* set : sets)
  {
    simplices<3>(set, 2, nullptr, offset, domain.triangles);
    simplices<4>(set, 3, nullptr, offset, domain.tetrahedra);
    offset += static_cast<int>(set->GetNumberOfPoints());
  }
  if (group.any(!domain.triangles.empty()) || !group.any(!domain.tetrahedra.empty()))
  {
    return domain;
  }
  // A volume mesh without surface cells: its boundary faces are the surface. Split over
  // processes, a piece's boundary also holds the faces it shares with another piece: those are
  // found by their vertices' positions on two processes, and left out.
  std::vector<vtkSmartPointer<vtkPolyData>> boundaries;
  std::vector<std::int64_t> keys;
  for (vtkPointSet* set : sets)
  {
    auto* grid = vtkUnstructuredGrid::SafeDownCast(set);
    if (!grid)
    {
      boundaries.emplace_back();
      continue;
    }
    vtkNew<vtkGeometryFilter> boundary;
    boundary->SetInputData(grid);
    boundary->SetPassThroughPointIds(true);
    boundary->SetOriginalPointIdsName("MLSOriginalPointIds");
    boundary->MergingOff();
    boundary->Update();
    boundaries.emplace_back(boundary->GetOutput());
    vtkPolyData* faces = boundaries.back();
    vtkNew<vtkIdList> ids;
    for (vtkIdType f = 0; group.size() > 1 && f < faces->GetNumberOfCells(); ++f)
    {
      faces->GetCellPoints(f, ids);
      std::uint64_t key = 0;
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        mlsdeform::Vec3 x;
        faces->GetPoint(ids->GetId(k), x.data());
        key += mlsdeform::positionKey(x); // a sum: the same for either side's vertex order
      }
      keys.push_back(static_cast<std::int64_t>(key));
    }
  }
  std::vector<std::int64_t> shared = group.size() > 1 ? group.gather(keys) : std::vector<std::int64_t>();
  std::sort(shared.begin(), shared.end());
  std::size_t face = 0;
  offset = 0;
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    if (vtkPolyData* faces = boundaries[s])
    {
      // The faces refer to renumbered points with their original ids in an array, or (the fast
      // path for unstructured grids) to the grid's own points.
      auto* ids = vtkIdTypeArray::SafeDownCast(faces->GetPointData()->GetArray("MLSOriginalPointIds"));
      if (group.size() > 1)
      {
        vtkNew<vtkCellArray> outer;
        vtkNew<vtkIdList> facePoints;
        for (vtkIdType f = 0; f < faces->GetNumberOfCells(); ++f, ++face)
        {
          const auto range = std::equal_range(shared.begin(), shared.end(), keys[face]);
          if (range.second - range.first < 2)
          {
            faces->GetCellPoints(f, facePoints);
            outer->InsertNextCell(facePoints);
          }
        }
        faces->SetPolys(outer); // the geometry filter's output holds polygons only
      }
      if (ids || faces->GetNumberOfPoints() == sets[s]->GetNumberOfPoints())
      {
        simplices<3>(faces, 2, ids ? ids->GetPointer(0) : nullptr, offset, domain.triangles);
      }
    }
    offset += static_cast<int>(sets[s]->GetNumberOfPoints());
  }
  return domain;
}

vtkGenericCell* CellsByType::get(vtkDataSet* set, vtkIdType cell)
{
  const auto type = static_cast<std::size_t>(set->GetCellType(cell));
  if (Cells.size() <= type)
  {
    Cells.resize(type + 1);
  }
  if (!Cells[type])
  {
    Cells[type] = vtkSmartPointer<vtkGenericCell>::New();
  }
  set->GetCell(cell, Cells[type]);
  return Cells[type];
}

void Stamp::add(vtkObject* object)
{
  objects.emplace_back(object, object ? object->GetMTime() : 0);
}

Stamp pointsStamp(const std::vector<vtkPointSet*>& sets)
{
  Stamp stamp;
  for (vtkPointSet* set : sets)
  {
    stamp.add(set->GetPoints()); // vtkPoints' MTime includes its data array's
  }
  return stamp;
}

Stamp cellsStamp(const std::vector<vtkPointSet*>& sets)
{
  Stamp stamp;
  // a cell array's MTime does not include its storage arrays': both count
  auto addCells = [&stamp](vtkCellArray* cells) {
    stamp.add(cells);
    stamp.add(cells ? cells->GetOffsetsArray() : nullptr);
    stamp.add(cells ? cells->GetConnectivityArray() : nullptr);
  };
  for (vtkPointSet* set : sets)
  {
    if (auto* poly = vtkPolyData::SafeDownCast(set))
    {
      addCells(poly->GetVerts());
      addCells(poly->GetLines());
      addCells(poly->GetPolys());
      addCells(poly->GetStrips());
    }
    else if (auto* grid = vtkUnstructuredGrid::SafeDownCast(set))
    {
      addCells(grid->GetCells());
      stamp.add(grid->GetCellTypesArray());
      stamp.add(grid->GetFaces());
      stamp.add(grid->GetFaceLocations());
    }
    else
    {
      stamp.add(set); // another point set type: any modification counts
    }
  }
  return stamp;
}

vtkSmartPointer<vtkPolyData> pointCloud(const mlsdeform::PointList& positions,
  const std::vector<std::pair<std::string, const std::vector<double>*>>& arrays)
{
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(positions.size()));
  vtkNew<vtkCellArray> vertices;
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    pts->SetPoint(static_cast<vtkIdType>(i), positions[i].data());
    const vtkIdType id = static_cast<vtkIdType>(i);
    vertices->InsertNextCell(1, &id);
  }
  cloud->SetPoints(pts);
  cloud->SetVerts(vertices);
  for (const auto& [name, values] : arrays)
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(name.c_str());
    array->SetNumberOfValues(static_cast<vtkIdType>(values->size()));
    std::copy(values->begin(), values->end(), array->GetPointer(0));
    cloud->GetPointData()->AddArray(array);
  }
  return cloud;
}

void reportProgress(void* algorithm, double fraction)
{
  static_cast<vtkAlgorithm*>(algorithm)->UpdateProgress(fraction);
}
}
