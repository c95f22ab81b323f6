// Face-based mesh quality as OpenFOAM's checkMesh defines it (primitiveMeshCheck, used in paper
// section 7.3): face centres and area vectors by triangle fans about the average point, cell
// centres and volumes by pyramids on the faces about the average face centre (any polyhedron),
// and per interior face
//   non-orthogonality = angle between the face area vector S_f and d = C_N - C_P (degrees),
//   skewness = |sv| / fd, sv the offset of the face centre from where the line P-N crosses the
//              face plane, fd the largest extent of the face along sv (at least 0.2 |d|);
// per boundary face (polyMeshTools::faceSkewness: "treat as if mirror cell on other side",
// primitiveMeshTools::boundaryFaceSkewness) the skewness with d = n (n . (C_f - C_P)), n = S_f /
// |S_f|, and fd at least 0.4 |d|: the interior formula with the owner mirrored across the face
// plane; no non-orthogonality (checkMesh's is 0 there).
#pragma once

#include "Common/CoreTypes.h"
#include "Common/UninitializedVector.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace mlsdeform
{
/// A polygon's centre (area weighted) and area vector (normal by the right-hand rule, length = area).
struct FaceGeometry
{
  Vec3 centre = Vec3::Zero();
  Vec3 area = Vec3::Zero();
};
FaceGeometry faceGeometry(const PointList& points, const int* face, std::size_t n);
inline FaceGeometry faceGeometry(const PointList& points, const std::vector<int>& face)
{
  return faceGeometry(points, face.data(), face.size());
}

/// A polyhedron's centre and volume from its faces (any orientation), or from their geometries.
struct CellGeometry
{
  Vec3 centre = Vec3::Zero();
  double volume = 0;
};
CellGeometry cellGeometry(const PointList& points, const std::vector<std::vector<int>>& faces);
CellGeometry cellGeometry(const std::vector<FaceGeometry>& faces);

/// OpenFOAM's face-pyramid check (checkMesh's "Face pyramids", the test of an inverted cell): a
/// face's pyramid with apex at the cell centre, S_f . (C_f - C) / 3, must have positive volume
/// with the face listed as seen from outside the cell (VTK's order; OpenFOAM's for the owner).
bool hasNegativePyramid(const std::vector<FaceGeometry>& faces, const Vec3& centre);

/// The cosine of the angle between a face's area vector S and d = N - P (cells with centres P
/// and N; S points from the owner P to the neighbour N, out of P, as in OpenFOAM), in [-1, 1].
double faceCosine(const Vec3& ownerCentre, const Vec3& neighbourCentre, const Vec3& area);

/// That angle in degrees: the face's non-orthogonality (a decreasing function of faceCosine, so
/// the largest over many faces is that of their smallest cosine).
double nonOrthogonalityOf(double cosine);
inline double nonOrthogonality(const Vec3& ownerCentre, const Vec3& neighbourCentre, const Vec3& area)
{
  return nonOrthogonalityOf(faceCosine(ownerCentre, neighbourCentre, area));
}

/// OpenFOAM's face skewness of an interior face (face points needed for its extent).
double skewness(const Vec3& ownerCentre, const Vec3& neighbourCentre, const FaceGeometry& face, const PointList& points,
  const int* faceIndices, std::size_t n);
inline double skewness(const Vec3& ownerCentre, const Vec3& neighbourCentre, const FaceGeometry& face, const PointList& points,
  const std::vector<int>& faceIndices)
{
  return skewness(ownerCentre, neighbourCentre, face, points, faceIndices.data(), faceIndices.size());
}

/// What a face's skewness is measured by: Cpf = C_f - P, the line d and the least extent fd's
/// share of |d|. An interior face: d = N - P, 0.2; a boundary face (OpenFOAM's
/// boundaryFaceSkewness): d = n (n . Cpf), the normal part of Cpf, 0.4 (0.2 of the mirrored cell's).
struct SkewFrame
{
  Vec3 Cpf;
  Vec3 d;
  double extentShare;
};
SkewFrame interiorFrame(const Vec3& ownerCentre, const Vec3& neighbourCentre, const FaceGeometry& face);
SkewFrame boundaryFrame(const Vec3& ownerCentre, const FaceGeometry& face);

/// OpenFOAM's skewness of a boundary face (its owner mirrored across the face plane).
double boundarySkewness(const Vec3& ownerCentre, const FaceGeometry& face, const PointList& points, const int* faceIndices, std::size_t n);

/// A cell as its list of faces, each a polygon of point indices.
using CellFaces = std::vector<std::vector<int>>;

/// The faces of many cells in flat arrays (a 1M-cell mesh as one CellFaces per cell made ~8M small
/// allocations): the faces of cell c are firstFace(c) .. firstFace(c + 1) - 1, numbered over all
/// cells, each a polygon of point indices.
class CellFaceList
{
public:
  CellFaceList() = default;
  explicit CellFaceList(const std::vector<CellFaces>& cells);

  /// Lists the faces of cells 0 .. count - 1 in parallel. Each thread makes its own visitor with
  /// newVisitor(); visitor(c, add) calls add(points, n) for each face of cell c, the same faces
  /// each time (it runs twice: to count them, then to store them in place).
  template <typename NewVisitor>
  static CellFaceList build(int count, NewVisitor newVisitor);

  int cells() const { return static_cast<int>(CellStart.size()) - 1; }
  long faces() const { return static_cast<long>(FaceStart.size()) - 1; }
  long firstFace(int cell) const { return CellStart[cell]; }
  const int* face(long f) const { return Points.data() + FaceStart[f]; }
  std::size_t faceSize(long f) const { return static_cast<std::size_t>(FaceStart[f + 1] - FaceStart[f]); }

private:
  // filled in parallel by build(), which sets every entry (first touched by the threads)
  UninitializedVector<long> CellStart{ 0 };
  UninitializedVector<long> FaceStart{ 0 };
  UninitializedVector<int> Points;
};

template <typename NewVisitor>
CellFaceList CellFaceList::build(int count, NewVisitor newVisitor)
{
  CellFaceList list;
  list.CellStart.resize(static_cast<std::size_t>(count) + 1);
  UninitializedVector<long> pointStart(static_cast<std::size_t>(count) + 1);
  list.CellStart[0] = pointStart[0] = 0;
#pragma omp parallel
  {
    auto visitor = newVisitor();
#pragma omp for schedule(dynamic, 4096)
    for (int c = 0; c < count; ++c)
    {
      long faces = 0, points = 0;
      visitor(c, [&](const auto*, std::size_t n) {
        ++faces;
        points += static_cast<long>(n);
      });
      list.CellStart[c + 1] = faces;
      pointStart[c + 1] = points;
    }
  }
  std::partial_sum(list.CellStart.begin(), list.CellStart.end(), list.CellStart.begin());
  std::partial_sum(pointStart.begin(), pointStart.end(), pointStart.begin());
  list.FaceStart.resize(static_cast<std::size_t>(list.CellStart.back()) + 1);
  list.FaceStart[0] = 0;
  list.Points.resize(static_cast<std::size_t>(pointStart.back()));
#pragma omp parallel
  {
    auto visitor = newVisitor();
#pragma omp for schedule(dynamic, 4096)
    for (int c = 0; c < count; ++c)
    {
      long face = list.CellStart[c], point = pointStart[c];
      visitor(c, [&](const auto* points, std::size_t n) {
        std::copy(points, points + n, list.Points.begin() + point);
        point += static_cast<long>(n);
        list.FaceStart[++face] = point;
      });
    }
  }
  return list;
}

/// A face shared by two cells; `face` is the owner's copy and `neighbourFace` the neighbour's (face
/// numbers of the CellFaceList).
struct InteriorFace
{
  int owner;
  int neighbour;
  long face;
  long neighbourFace;
};
/// Many, written in parallel (3M faces, 72 MB, on a 1M-cell mesh: first touched by the threads).
using InteriorFaces = UninitializedVector<InteriorFace>;

/// The faces shared by two cells, matched by their point sets (the owner is the lower cell index).
/// Throws std::invalid_argument for a face shared by more than two cells.
InteriorFaces interiorFaces(const CellFaceList& cells);

/// The centre and volume of cell `cell` of a CellFaceList on these points.
CellGeometry cellGeometry(const PointList& points, const CellFaceList& cells, int cell);

/// A face of one cell only: its number in the CellFaceList and that cell.
struct BoundaryFace
{
  int owner;
  long face;
};
using BoundaryFaces = std::vector<BoundaryFace>;

/// The faces of the cells that are no copy of an interior face, in face order.
BoundaryFaces boundaryFaces(const CellFaceList& cells, const InteriorFaces& interior);

/// Per boundary face, a key of its points' positions that does not depend on their order (the
/// bits of their sorted coordinates, mixed): two pieces of one mesh (blocks, processes, cells
/// whose points were not merged) touch at the faces of equal keys, which are not on the mesh's
/// boundary. Two different faces share a key with probability 2^-64 a pair.
std::vector<std::uint64_t> boundaryKeys(const PointList& points, const CellFaceList& cells, const BoundaryFaces& boundary);

/// The keys that occur more than once in keys, sorted.
std::vector<std::uint64_t> repeatedKeys(std::vector<std::uint64_t> keys);

/// The boundary faces whose key (keys, one per face) is not in `between` (sorted): those on the
/// mesh's boundary, not between its pieces. Returns how many were left out.
long leaveOutFaces(BoundaryFaces& boundary, const std::vector<std::uint64_t>& keys, const std::vector<std::uint64_t>& between);

/// A mesh's cells as lists of faces, the faces between two cells and those on its boundary.
struct MeshFaces
{
  CellFaceList cells;
  InteriorFaces interior;
  BoundaryFaces boundary;
};

/// The mesh of these cells: its interior faces matched by their points (interiorFaces), its
/// boundary faces the others.
MeshFaces meshFaces(CellFaceList cells);

/// The cells' faces and the interior faces of a mesh in OpenFOAM's form (polyMesh), without
/// matching faces by their points: face f, the points points[start[f]] .. points[start[f + 1] - 1]
/// listed so that their normal points out of owner[f], lies between owner[f] and neighbour[f] for
/// f < neighbour.size() and on the boundary of owner[f] after (the boundary faces, in face order). The cells are 0 .. the largest
/// owner or neighbour; each lists its faces in face order, those it is the neighbour of reversed
/// (out of the cell, as VTK lists a cell's faces); an interior face's copy is its owner's. Throws
/// std::invalid_argument when the lists' sizes disagree, a cell or point index is out of range
/// (points: 0 .. pointCount - 1), a face's owner is its neighbour, or a cell has no face.
MeshFaces ownerNeighbourFaces(const std::vector<int>& start, const std::vector<int>& points, const std::vector<int>& owner,
  const std::vector<int>& neighbour, int pointCount);

/// Per interior face, +1 or -1 so that the oriented area vector points out of the owner on
/// `points`. OpenFOAM fixes that order in the topology, so decide it on the undeformed mesh and
/// keep it: a neighbour whose centre folds over to the owner's side then shows above 90 degrees.
std::vector<int> faceOrientation(const PointList& points, const MeshFaces& mesh);

/// The largest non-orthogonality (degrees) over the interior faces and skewness over the interior
/// and boundary faces and, when asked for (perFace), those of every face; the cells with a pyramid of negative volume
/// (inverted, hasNegativePyramid) and their number. A summary without the per-face values takes
/// no face-sized buffer and one arc cosine in all.
struct FaceMeasures
{
  bool perFace = true;
  std::vector<double> nonOrthogonality; // per interior face, when perFace
  std::vector<double> skewness;         // per interior face, when perFace
  std::vector<double> boundarySkewness; // per boundary face, when perFace
  double maxNonOrthogonality = 0;
  double maxSkewness = 0;
  std::vector<unsigned char> inverted; // per cell
  long invertedCells = 0;
};
FaceMeasures faceMeasures(const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation);

/// The mesh-sized buffers of faceMeasures, kept between calls on the same cells and interior
/// faces so that measuring another deformation allocates nothing. Each interior face's geometry
/// is computed once, from its owner's copy, and serves both its cells and its measures, as
/// OpenFOAM computes it (three times as often before: 52% of a 400k-point verdict's time).
struct FaceWorkspace
{
  std::vector<Vec3> centres;       // per cell
  std::vector<FaceGeometry> faces; // per interior face, out of its owner as listed
  std::vector<int> interiorOf;     // per face of the cells: i for interior face i's owner's copy,
                                   // -2 - i for its neighbour's, interior + b for boundary face b,
                                   // -1 for another face
  long boundaryFaces = -1;         // the boundary faces interiorOf was made for
  std::vector<double> boundarySkewness; // per boundary face
  std::vector<double> screen;      // per face measured: faceTail's cosine or skewness bound
};

/// faceMeasures into out (per face as out.perFace says), with the buffers of work.
void faceMeasures(
  const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation, FaceWorkspace& work, FaceMeasures& out);

/// The faces whose measure (the non-orthogonality of an interior face, or with `skewness` the
/// skewness of an interior or boundary face) is at least largest - width, numbered interior faces
/// first (i), then boundary faces (interior.size() + b), in that order, with their measures and
/// the largest over every face;
/// the faces' and cells' geometry of these points in work. One pass over the cells and one over
/// the faces, which keeps their cosines (or skewness bounds, in work.screen): a face's arc cosine
/// (or its points' extent) is computed only where it may lie within width of the largest.
struct FaceTail
{
  double largest = 0;
  std::vector<long> faces;
  std::vector<double> values;
};
FaceTail faceTail(
  const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation, bool skewness, double width, FaceWorkspace& work);

/// faceOrientation, and with it the measures of these points into out (with the buffers of work):
/// the rest mesh's measures at the cost of one pass over its cells.
std::vector<int> faceOrientation(const PointList& points, const MeshFaces& mesh, FaceWorkspace& work, FaceMeasures& out);
} // namespace mlsdeform
