// Face-based mesh quality as OpenFOAM's checkMesh defines it (primitiveMeshCheck, used in paper
// section 7.3): face centres and area vectors by triangle fans about the average point, cell
// centres and volumes by pyramids on the faces about the average face centre (any polyhedron),
// and per interior face
//   non-orthogonality = angle between the face area vector S_f and d = C_N - C_P (degrees),
//   skewness = |sv| / fd, sv the offset of the face centre from where the line P-N crosses the
//              face plane, fd the largest extent of the face along sv (at least 0.2 |d|).
#pragma once

#include "CoreTypes.h"

#include <vector>

namespace mlsdeform
{
/// A polygon's centre (area weighted) and area vector (normal by the right-hand rule, length = area).
struct FaceGeometry
{
  Vec3 centre = Vec3::Zero();
  Vec3 area = Vec3::Zero();
};
FaceGeometry faceGeometry(const PointList& points, const std::vector<int>& face);

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

/// Non-orthogonality in degrees of a face with area vector S between cells with centres P and N;
/// S points from the owner P to the neighbour N (out of P), as in OpenFOAM.
double nonOrthogonality(const Vec3& ownerCentre, const Vec3& neighbourCentre, const Vec3& area);

/// OpenFOAM's face skewness of an interior face (face points needed for its extent).
double skewness(const Vec3& ownerCentre, const Vec3& neighbourCentre, const FaceGeometry& face, const PointList& points,
  const std::vector<int>& faceIndices);

/// A cell as its list of faces, each a polygon of point indices.
using CellFaces = std::vector<std::vector<int>>;

/// A face shared by two cells; `face` indexes the owner's face list.
struct InteriorFace
{
  int owner = -1;
  int neighbour = -1;
  int face = -1;
};

/// The faces shared by two cells, matched by their point sets (the owner is the lower cell index).
/// Throws std::invalid_argument for a face shared by more than two cells.
std::vector<InteriorFace> interiorFaces(const std::vector<CellFaces>& cells);

/// Per interior face, +1 or -1 so that the oriented area vector points out of the owner on
/// `points`. OpenFOAM fixes that order in the topology, so decide it on the undeformed mesh and
/// keep it: a neighbour whose centre folds over to the owner's side then shows above 90 degrees.
std::vector<int> faceOrientation(
  const PointList& points, const std::vector<CellFaces>& cells, const std::vector<InteriorFace>& faces);

/// Non-orthogonality (degrees) and skewness of every interior face; the cells with a pyramid of
/// negative volume (inverted, hasNegativePyramid) and their number.
struct FaceMeasures
{
  std::vector<double> nonOrthogonality;
  std::vector<double> skewness;
  std::vector<unsigned char> inverted; // per cell
  long invertedCells = 0;
};
FaceMeasures faceMeasures(const PointList& points, const std::vector<CellFaces>& cells,
  const std::vector<InteriorFace>& faces, const std::vector<int>& orientation);
} // namespace mlsdeform
