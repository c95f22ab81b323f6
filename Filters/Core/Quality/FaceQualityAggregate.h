// The mesh's quality as one smooth function of its points, for an optimizer's constraint (DAFoam's
// KS-aggregated mesh quality): the Kreisselmeier-Steinhauser aggregate of checkMesh's
// non-orthogonality (degrees) over the interior faces or skewness over the interior and boundary
// faces (FaceQuality.h), in its
// max-shifted form
//   KS = m + ln(sum_f exp(rho (q_f - m))) / rho,   m = max_f q_f,   m <= KS <= m + ln(N) / rho,
// and its exact gradient at the points by reverse-mode differentiation of FaceQuality's
// definitions (face centres and areas by triangle fans, cell centres by face pyramids):
//   dKS/dX = sum_f w_f dq_f/dX,  w_f = exp(rho (q_f - m)) / sum.
// Faces with w_f < 1e-20 are left out of the gradient (their weights sum to at most N 1e-20). A
// perfectly orthogonal face's angle has no derivative (a cone at 0 degrees): it adds none.
#pragma once

#include "Quality/FaceQuality.h"

#include <limits>

namespace mlsdeform
{
/// The measures aggregated: checkMesh's face measures here, the elements' scaled Jacobian by
/// ElementJacobian's scaledJacobians (the same AggregatePart over -sj).
enum class QualityMeasure
{
  NonOrthogonality,
  Skewness,
  ScaledJacobian,
};

/// Terms of a smaller weight w = exp(rho (q - m)) / sum are left out of the gradients.
constexpr double LeastAggregateWeight = 1e-20;

/// The pieces of a KS aggregate over several meshes or processes: m, sum exp(rho (q - m)) and N.
struct AggregatePart
{
  double largest = -std::numeric_limits<double>::infinity();
  double sum = 0;
  long count = 0;

  /// The two parts' union (the same from either order up to round-off of the sum).
  void add(const AggregatePart& other, double rho);
  double value(double rho) const;
};

/// The part of values q (the elements' measures; one part of the tests' faces).
AggregatePart aggregatePart(const std::vector<double>& q, double rho);

/// The part of a face measure (NonOrthogonality over the interior faces, Skewness over the
/// interior and boundary faces) on these points, and the faces that weigh in it: those within (ln N + 46) / rho of the largest
/// (FaceQuality's faceTail). The others' terms exp(rho (q - m)) are below e^-46 / N each, their
/// sum below 1e-20 of the sum (at least 1): under a double's round-off, and none of them is heavy
/// enough for the gradient. work holds the geometry the gradient needs.
struct FaceAggregate
{
  AggregatePart part;
  FaceTail tail;
};
FaceAggregate aggregateFaces(const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation, QualityMeasure measure,
  double rho, FaceWorkspace& work);

/// Adds sum_f w_f dq_f/dX to gradient (one entry per point), the weights of the aggregate `whole`
/// (over every part); work and tail as aggregateFaces left them on these points. The faces' terms
/// are summed in face order: the same bits for any thread count.
void addAggregateGradient(const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation, const FaceWorkspace& work,
  const FaceTail& tail, QualityMeasure measure, double rho, const AggregatePart& whole, PointList& gradient);

/// One face between cells with centres P (its owner's, cell `owner`) and N, as the owner lists
/// it (face number `face`, its area times sign): weight times its measure's derivatives at the
/// owner's points (the face's and the cell's) added to gradient, and those along N returned (for
/// addCellCentreGradient at the neighbour's points: a face between two pieces of a mesh).
Vec3 addFaceMeasureGradient(const PointList& points, const CellFaceList& cells, int owner, long face, int sign, const Vec3& P,
  const Vec3& N, QualityMeasure measure, double weight, PointList& gradient);

/// Adds d(centre of cell `cell`)/dX contracted with centreBar to gradient.
void addCellCentreGradient(const PointList& points, const CellFaceList& cells, int cell, const Vec3& centreBar, PointList& gradient);

/// The reverse-mode derivatives of FaceQuality's geometry: given dF/d(centre) and dF/d(area) of a
/// face, adds dF/d(its k-th point) to cornerBar[k] (k = 0 .. n-1).
void faceGeometryAdjoint(
  const PointList& points, const int* face, std::size_t n, const Vec3& centreBar, const Vec3& areaBar, Vec3* cornerBar);

/// Given dF/d(centre) and dF/d(volume) of a cell with these faces' geometries, adds dF/d(face
/// centre) and dF/d(face area) of each face to centreBar[f] and areaBar[f].
void addCellGeometryAdjoint(const std::vector<FaceGeometry>& faces, const Vec3& cellCentreBar, double volumeBar,
  std::vector<Vec3>& centreBar, std::vector<Vec3>& areaBar);
} // namespace mlsdeform
