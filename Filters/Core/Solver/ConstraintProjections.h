// Shape-Up projections (Bouaziz et al. [21], paper section 6.2): for the current positions of a
// constrained point set, the closest positions (in the least-squares sense) that satisfy the
// constraint. The alternating optimization pulls the deformation towards them (eq. 15-17).
#pragma once

#include "Common/CoreTypes.h"
#include "Solver/ReferenceSurface.h"

namespace mlsdeform
{
/// A plane through point with unit normal; farthest: the largest distance of the points it was
/// fitted to.
struct Plane
{
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double farthest = 0;

  /// x moved along the normal onto the plane.
  Vec3 project(const Vec3& x) const { return x - normal.dot(x - point) * normal; }
};

/// The least-squares plane of at least 3 points: through their mean, normal along the
/// covariance's smallest principal direction. A normal within 1e-9 of a coordinate axis is
/// that axis exactly (a ground or symmetry plane of a CFD domain: motions within it then keep
/// that coordinate exactly).
Plane fitPlane(const PointList& x);

/// Onto the least-squares plane (fitPlane).
PointList projectToPlane(const PointList& x);

/// Onto a given plane: the slip constraint, whose points slide within their rest plane.
PointList projectTo(const Plane& plane, const PointList& x);

/// Onto the least-squares plane, then onto the least-squares circle in it (algebraic fit of
/// Kasa, refined by Gauss-Newton on the geometric distances).
PointList projectToCircle(const PointList& x);

/// Onto the least-squares cylinder of Eberly, "Least Squares Fitting of Data by Linear or
/// Quadratic Structures" (Geometric Tools, 2019), section "Fitting a Cylinder" [36]: for an axis
/// direction W the center and radius have closed forms, and W minimizes the remaining error.
/// axis is the search's start and returns the fitted direction (zero: search all directions).
PointList projectToCylinder(const PointList& x, Vec3& axis);

/// The best similarity transform (rotation, translation, uniform scale) of the rest positions
/// onto x, applied to the rest positions (Umeyama 1991): the feature-line constraint.
PointList projectToSimilarity(const PointList& rest, const PointList& x);

/// The best rigid transform (rotation, translation) of the rest positions onto x, applied to the
/// rest positions (Kabsch / Umeyama without scale): the rigid constraint.
PointList projectToRigid(const PointList& rest, const PointList& x);

/// The mirror image of every rest position among the rest positions: partner[i] is the index of
/// the position nearest to x_i reflected in the plane, or -1 when that one lies farther than
/// tolerance (the positions are not symmetric about the plane there).
std::vector<int> mirrorPartners(const PointList& rest, const Plane& mirror, double tolerance);

/// The nearest displacement field that is mirror-symmetric about the plane: with d = x - rest and
/// R = I - 2 n n^T, position i gets rest_i + (d_i + R d_partner(i)) / 2 (an orthogonal projection:
/// the pairs are an involution). The symmetric constraint.
PointList projectToSymmetric(const PointList& rest, const PointList& x, const std::vector<int>& partner, const Plane& mirror);

/// The mean of the points.
Vec3 centroid(const PointList& x);

/// The translations of two point sets that bring their centroids to the distance a Distance
/// constraint keeps: along axis (a unit vector; zero: along the line of the centroids) by
/// distance, shared in inverse proportion to the sets' sizes (the smallest move of all points).
/// Returns the first set's translation; the second's is minus it times na / nb.
Vec3 distanceTranslation(const PointList& a, const PointList& b, const Vec3& axis, double distance);

/// Each position that came nearer to the reference surface than bound, or crossed it, moved to
/// bound from the surface on its rest side (side: +1 or -1 per position, the side of the
/// triangle's normal it lay on at rest); the others as they are. The Offset constraint: a
/// lower bound, active only where violated.
PointList projectOutside(const ReferenceSurface& reference, const PointList& x, const std::vector<double>& side, double bound);
} // namespace mlsdeform
