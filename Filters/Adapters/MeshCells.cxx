#include "Adapters/MeshCells.h"

#include "Adapters/CellFaces.h"
#include "Adapters/PointSets.h"
#include "Adapters/TypedPoints.h"
#include "Common/PositionHash.h"
#include <vtkCell.h>
#include <vtkCellArray.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkDataSetAttributes.h>
#include <vtkGenericCell.h>
#include <vtkGeometryFilter.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <algorithm>
#include <array>
#include <atomic>
#include <tuple>

namespace mlsvtk
{
namespace
{
// Orders point ids by their positions (lexicographically): a cell's split into simplices chosen
// in this order depends on its geometry only, not on how the cell or the mesh numbers its points
// (a mesh decomposed over processes numbers them differently than the whole mesh).
// Compares the coordinates in place when they are floats or doubles (a cell asks about 40 times).
class PositionOrder
{
public:
  explicit PositionOrder(vtkPoints* points)
    : Points(points)
  {
    withTypedPoints(points->GetData(), [this](const auto* values) { keep(values); });
  }
  bool operator()(vtkIdType a, vtkIdType b) const
  {
    if (Floats)
    {
      return std::lexicographical_compare(Floats + 3 * a, Floats + 3 * a + 3, Floats + 3 * b, Floats + 3 * b + 3);
    }
    if (Doubles)
    {
      return std::lexicographical_compare(Doubles + 3 * a, Doubles + 3 * a + 3, Doubles + 3 * b, Doubles + 3 * b + 3);
    }
    double pa[3], pb[3];
    Points->GetPoint(a, pa);
    Points->GetPoint(b, pb);
    return std::lexicographical_compare(pa, pa + 3, pb, pb + 3);
  }

private:
  void keep(const float* values) { Floats = values; }
  void keep(const double* values) { Doubles = values; }

  vtkPoints* Points;
  const float* Floats = nullptr;
  const double* Doubles = nullptr;
};

// The triangles of a polygon (a cycle of point ids): a fan from its first point in position
// order, so that two cells sharing a face split it alike.
template <typename Add>
void fan(const vtkIdType* polygon, vtkIdType n, const PositionOrder& before, Add add)
{
  const vtkIdType first = std::min_element(polygon, polygon + n, before) - polygon;
  for (vtkIdType v = 1; v + 1 < n; ++v)
  {
    add({ polygon[first], polygon[(first + v) % n], polygon[(first + v + 1) % n] });
  }
}

// The tetrahedra of a 3D cell given by its faces (faces(visit) calls visit(ids, n) per face): the
// cell is star-shaped about its vertices (convex cells and OpenFOAM's are), so its first point
// in position order joined to the fans of the faces that do not hold it splits it.
// vtkPolyhedron::Triangulate builds a Delaunay tetrahedralization and a polyhedron object per
// cell, most of the sampling's time on a snappyHexMesh mesh.
template <typename Faces, typename Add>
void starTetrahedra(Faces faces, const PositionOrder& before, Add add)
{
  vtkIdType apex = -1;
  faces([&](const vtkIdType* face, vtkIdType n) {
    for (vtkIdType k = 0; k < n; ++k)
    {
      apex = apex < 0 || before(face[k], apex) ? face[k] : apex;
    }
  });
  faces([&](const vtkIdType* face, vtkIdType n) {
    if (std::find(face, face + n, apex) == face + n)
    {
      fan(face, n, before, [&](const std::array<vtkIdType, 3>& t) { add({ apex, t[0], t[1], t[2] }); });
    }
  });
}

// Splits every cell of the given dimension into simplices (triangles or tetrahedra), whatever
// the numbering of its points: simplices are taken as they are, polygons (quads, pixels) become
// fans and 3D cells of fixed topology and polyhedra tetrahedra about a point (chosen by position
// order); other cells (quadratic ones) are triangulated by VTK. Chunks of cells are split in
// parallel and appended in cell order, so the list does not depend on the thread count.
template <std::size_t N>
void simplices(vtkDataSet* set, int dimension, const vtkIdType* pointMap, int offset, mlsdeform::Simplices<N>& out)
{
  const int simplexType = N == 3 ? VTK_TRIANGLE : VTK_TETRA;
  auto* pointSet = vtkPointSet::SafeDownCast(set);
  if (!pointSet || !pointSet->GetPoints())
  {
    return;
  }
  if (auto* polyData = vtkPolyData::SafeDownCast(set); polyData && polyData->NeedToBuildCells())
  {
    polyData->BuildCells(); // before the threads: GetCellPoints would build it on first use
  }
  const PositionOrder before(pointSet->GetPoints());
  auto* grid = vtkUnstructuredGrid::SafeDownCast(set);
  vtkUnsignedCharArray* ghosts = set->GetCellGhostArray();
  const vtkIdType cellCount = set->GetNumberOfCells();
  constexpr vtkIdType Chunk = 16384;
  std::vector<std::vector<std::array<int, N>>> parts(static_cast<std::size_t>((cellCount + Chunk - 1) / Chunk));
#pragma omp parallel
  {
    CellsByType cells;
    vtkNew<vtkIdList> ids;
    vtkNew<vtkPoints> pts;
#pragma omp for schedule(dynamic)
    for (long part = 0; part < static_cast<long>(parts.size()); ++part)
    {
      std::vector<std::array<int, N>>& simplexList = parts[part];
      auto add = [&](const std::array<vtkIdType, N>& simplex) {
        std::array<int, N> mapped;
        for (std::size_t v = 0; v < N; ++v)
        {
          mapped[v] = offset + static_cast<int>(pointMap ? pointMap[simplex[v]] : simplex[v]);
        }
        simplexList.push_back(mapped);
      };
      for (vtkIdType c = part * Chunk; c < std::min(cellCount, (part + 1) * Chunk); ++c)
      {
        if (ghosts && (ghosts->GetValue(c) & vtkDataSetAttributes::DUPLICATECELL))
        {
          continue; // another process's cell, sampled there
        }
        const int type = set->GetCellType(c);
        if (type != simplexType && cellDimension(type) != dimension)
        {
          continue;
        }
        set->GetCellPoints(c, ids);
        vtkIdType* cellPoints = ids->GetPointer(0);
        const vtkIdType n = ids->GetNumberOfIds();
        if (type == simplexType)
        {
          std::array<vtkIdType, N> simplex;
          std::copy_n(cellPoints, N, simplex.begin());
          add(simplex);
          continue;
        }
        if constexpr (N == 3)
        {
          if (type == VTK_POLYGON || type == VTK_QUAD || type == VTK_PIXEL)
          {
            if (type == VTK_PIXEL)
            {
              std::swap(cellPoints[2], cellPoints[3]);
            }
            fan(cellPoints, n, before, add);
            continue;
          }
        }
        else
        {
          if (type == VTK_POLYHEDRON && grid)
          {
            starTetrahedra([&](auto visit) { visitPolyhedronFaces(grid, c, visit); }, before, add);
            continue;
          }
          // the linear types of fixed topology (hexahedron, voxel, wedge, pyramid, pentagonal and
          // hexagonal prism): their faces as positions in the point list, asked of VTK once per type
          // (a vtkGenericCell per cell took most of the sampling domain's time on a 1M-cell mesh)
          if (const LocalFaces& local = cellTypeFaces(type); vtkCellTypes::IsLinear(type) && !local.empty())
          {
            starTetrahedra(
              [&](auto visit) {
                for (const std::vector<int>& face : local)
                {
                  std::array<vtkIdType, 6> global; // a hexagonal prism's faces have 6 points at most
                  for (std::size_t k = 0; k < face.size(); ++k)
                  {
                    global[k] = cellPoints[face[k]];
                  }
                  visit(global.data(), static_cast<vtkIdType>(face.size()));
                }
              },
              before, add);
            continue;
          }
        }
        if (!cells.get(set, c)->Triangulate(0, ids, pts))
        {
          continue;
        }
        for (vtkIdType s = 0; s + static_cast<vtkIdType>(N) <= ids->GetNumberOfIds(); s += N)
        {
          std::array<vtkIdType, N> simplex;
          std::copy_n(ids->GetPointer(s), N, simplex.begin());
          add(simplex);
        }
      }
    }
  }
  // appended in parallel: each part copied by one thread into its place
  std::vector<std::size_t> start(parts.size() + 1, out.size());
  for (std::size_t part = 0; part < parts.size(); ++part)
  {
    start[part + 1] = start[part] + parts[part].size();
  }
  out.resize(start.back());
#pragma omp parallel for schedule(static)
  for (long part = 0; part < static_cast<long>(parts.size()); ++part)
  {
    std::copy(parts[part].begin(), parts[part].end(), out.begin() + start[part]);
    std::vector<std::array<int, N>>().swap(parts[part]);
  }
}

// The boundary of a grid with nonlinear cells (a deck's C3D10, C3D20), over the grid's own points:
// each face that one cell alone has, as the polygon around its corners and edge nodes
// (cellTypeFaces), in the cells' order and oriented out of them as VTK's cell faces are. A face is
// found by its four least node ids: two faces of a conforming mesh share at most an edge, three
// nodes. (vtkGeometryFilter of VTK 9.2 gives such faces float points and original point ids that
// do not name the grid's points.)
vtkSmartPointer<vtkPolyData> nonlinearBoundary(vtkUnstructuredGrid* grid)
{
  struct Face
  {
    std::array<vtkIdType, 4> key; // the least node ids, sorted; -1 after a face's last
    vtkIdType cell;
    int face;
    bool operator<(const Face& other) const { return std::tie(key, cell, face) < std::tie(other.key, other.cell, other.face); }
  };
  std::vector<Face> faces;
  const vtkIdType* points = nullptr;
  vtkIdType count = 0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const LocalFaces& local = cellTypeFaces(grid->GetCellType(c));
    if (local.empty())
    {
      continue; // 2D cells, and 3D types without a face table (none a deck has)
    }
    grid->GetCellPoints(c, count, points);
    for (std::size_t f = 0; f < local.size(); ++f)
    {
      std::array<vtkIdType, 8> ids; // a quadratic quadrilateral's 8 nodes at most
      const std::size_t n = std::min(local[f].size(), ids.size());
      for (std::size_t k = 0; k < n; ++k)
      {
        ids[k] = points[local[f][k]];
      }
      std::sort(ids.begin(), ids.begin() + static_cast<long>(n));
      Face entry{ { -1, -1, -1, -1 }, c, static_cast<int>(f) };
      std::copy_n(ids.begin(), std::min<std::size_t>(n, 4), entry.key.begin());
      faces.push_back(entry);
    }
  }
  std::sort(faces.begin(), faces.end());
  vtkNew<vtkCellArray> polygons;
  std::vector<vtkIdType> polygon;
  std::vector<std::pair<vtkIdType, int>> boundary;
  for (std::size_t i = 0; i < faces.size();)
  {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key)
    {
      ++j;
    }
    if (j == i + 1)
    {
      boundary.emplace_back(faces[i].cell, faces[i].face);
    }
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());
  for (const auto& [c, f] : boundary)
  {
    grid->GetCellPoints(c, count, points);
    polygon.clear();
    for (int k : cellTypeFaces(grid->GetCellType(c))[static_cast<std::size_t>(f)])
    {
      polygon.push_back(points[k]);
    }
    polygons->InsertNextCell(static_cast<vtkIdType>(polygon.size()), polygon.data());
  }
  vtkNew<vtkPolyData> out;
  out->SetPoints(grid->GetPoints());
  out->SetPolys(polygons);
  return out;
}

bool hasNonlinearCells(vtkUnstructuredGrid* grid)
{
  vtkUnsignedCharArray* types = grid->GetDistinctCellTypesArray();
  for (vtkIdType t = 0; types && t < types->GetNumberOfValues(); ++t)
  {
    if (!vtkCellTypes::IsLinear(types->GetValue(t)))
    {
      return true;
    }
  }
  return false;
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

std::vector<BoundaryFaces> boundaryFaces(const std::vector<vtkPointSet*>& sets, const mlsdeform::Collective& group)
{
  // Split over processes, a piece's boundary also holds the faces it shares with another piece:
  // those are found by their vertices' positions on two processes, and left out.
  std::vector<BoundaryFaces> boundaries(sets.size());
  std::vector<std::int64_t> keys;
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    auto* grid = vtkUnstructuredGrid::SafeDownCast(sets[s]);
    if (!grid)
    {
      continue;
    }
    if (hasNonlinearCells(grid))
    {
      boundaries[s].faces = nonlinearBoundary(grid);
    }
    else
    {
      vtkNew<vtkGeometryFilter> boundary;
      boundary->SetInputData(grid);
      boundary->SetPassThroughPointIds(true);
      boundary->SetOriginalPointIdsName("MLSOriginalPointIds");
      boundary->MergingOff();
      boundary->Update();
      boundaries[s].faces = boundary->GetOutput();
    }
    vtkPolyData* faces = boundaries[s].faces;
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
  for (BoundaryFaces& b : boundaries)
  {
    if (!b.faces)
    {
      continue;
    }
    if (group.size() > 1)
    {
      vtkNew<vtkCellArray> outer;
      vtkNew<vtkIdList> facePoints;
      for (vtkIdType f = 0; f < b.faces->GetNumberOfCells(); ++f, ++face)
      {
        const auto range = std::equal_range(shared.begin(), shared.end(), keys[face]);
        if (range.second - range.first < 2)
        {
          b.faces->GetCellPoints(f, facePoints);
          outer->InsertNextCell(facePoints);
        }
      }
      b.faces->SetPolys(outer); // the geometry filter's output holds polygons only
    }
    // The faces refer to renumbered points with their original ids in an array, or (the fast
    // path for unstructured grids) to the grid's own points.
    auto* ids = vtkIdTypeArray::SafeDownCast(b.faces->GetPointData()->GetArray("MLSOriginalPointIds"));
    b.originalIds = ids ? ids->GetPointer(0) : nullptr;
  }
  return boundaries;
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
  // A volume mesh without surface cells: its boundary faces are the surface.
  const std::vector<BoundaryFaces> boundaries = boundaryFaces(sets, group);
  offset = 0;
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    if (const BoundaryFaces& b = boundaries[s]; b.faces && (b.originalIds || b.faces->GetNumberOfPoints() == sets[s]->GetNumberOfPoints()))
    {
      simplices<3>(b.faces, 2, b.originalIds, offset, domain.triangles);
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
} // namespace mlsvtk
