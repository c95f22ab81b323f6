// The geometric primitives of the automatic constraint detection (paper section 6.3, Fig. 7):
// planes, cylinders, spheres and cones, as the efficient RANSAC of Schnabel, Wahl and Klein 2007
// ("Efficient RANSAC for point-cloud shape detection", [39], section 4) uses them: each is built
// from a minimal set of oriented samples (points with unit normals), measures the distance and
// the surface normal at a sample, and is refit to an inlier set by least squares.
#pragma once

#include "Common/CoreTypes.h"

#include <cmath>
#include <optional>

namespace mlsdeform
{
enum class PrimitiveType
{
  Plane = 0,
  Cylinder = 1,
  Sphere = 2,
  Cone = 3
};

/// "Plane", "Cylinder", "Sphere", "Cone".
const char* primitiveTypeName(PrimitiveType type);

/// The parameters that determine a primitive of the type (its degrees of freedom): plane 3
/// (normal and offset), sphere 4, cylinder 5 (axis direction 2, axis point 2, radius), cone 6.
int parameterCount(PrimitiveType type);

struct Primitive
{
  PrimitiveType type = PrimitiveType::Plane;
  Vec3 axis = Vec3::UnitZ();     // plane: unit normal; cylinder, cone: unit axis (cone: into its opening)
  double offset = 0;             // plane: axis . x = offset
  Vec3 center = Vec3::Zero();    // sphere: center; cylinder: a point on the axis; cone: apex
  double radius = 0;             // sphere, cylinder
  double angle = 0;              // cone: half opening angle (radians); set it with setAngle
  double cosAngle = 1, sinAngle = 0; // cone: its cosine and sine (distances need them per sample)

  void setAngle(double a)
  {
    angle = a;
    cosAngle = std::cos(a);
    sinAngle = std::sin(a);
  }

  /// Unsigned distance of x from the surface (a cone is one infinite nappe).
  double distance(const Vec3& x) const;
  /// The same, and the unit surface normal at the point of the surface closest to x (up to
  /// sign), in one evaluation.
  double distance(const Vec3& x, Vec3& normal) const;
  /// The unit surface normal at the point of the surface closest to x (up to sign).
  Vec3 normalAt(const Vec3& x) const;
  /// Compatible with an oriented sample (Schnabel et al. section 4.4): within epsilon of the
  /// surface and |n . normalAt(x)| >= cosAlpha (the normal only for samples within epsilon).
  bool compatible(const Vec3& x, const Vec3& n, double epsilon, double cosAlpha) const
  {
    return distance(x) < epsilon && std::abs(n.dot(normalAt(x))) >= cosAlpha;
  }
};

/// The candidate of that type through three oriented samples (Schnabel et al. section 4.1):
/// plane through the points; sphere and cylinder from the first two samples' normal lines;
/// cone from the tangent planes (apex) and the directions to the samples (axis). Nothing when
/// the samples determine none (collinear points, parallel normals, a cone flatter or
/// narrower than MinimumConeAngle) or when one of the three samples is not compatible with it.
std::optional<Primitive> fitMinimal(PrimitiveType type, const Vec3 (&p)[3], const Vec3 (&n)[3], double epsilon, double cosAlpha);

/// The RMS and the largest distance of the subset of points from the surface (0 for none).
struct DistanceStatistics
{
  double rms = 0, max = 0;
};
DistanceStatistics distanceStatistics(const Primitive& shape, const PointList& points, const std::vector<int>& subset);

/// Loops over fewer samples than this run on one thread: starting the threads would cost more
/// than the loop (a forward search or a fit on a small primitive runs thousands of them).
constexpr long ParallelSamples = 4096;

/// Cones with a half angle outside [MinimumConeAngle, pi/2 - MinimumConeAngle] are left to the
/// cylinder and the plane, which they approximate.
constexpr double MinimumConeAngle = 0.05; // radians (about 3 degrees)

/// The least-squares fit to the samples subset of points: a plane by principal components (the
/// start's normal through their mean if they are collinear); a
/// cylinder, sphere or cone by Levenberg-Marquardt on the geometric distances started from
/// start. weights (optional, one per sample of subset, positive): the squared distances are
/// weighted. Returns start when the subset is too small to determine the primitive.
Primitive fitLeastSquares(const Primitive& start, const PointList& points, const std::vector<int>& subset,
  const std::vector<double>* weights = nullptr);

/// The fit that (nearly) minimises the largest distance of the subset's points (a minimax or
/// Chebyshev fit), from start: Lawson's iteratively reweighted least squares, the iterate with
/// the least largest distance (start if none is better), stopped once that is below enough.
/// Where least squares leaves the ends of a blend surface just beyond epsilon, this fit can
/// hold all its samples within epsilon.
Primitive fitMinimax(const Primitive& start, const PointList& points, const std::vector<int>& subset, double enough = 0,
  int iterations = 20);
} // namespace mlsdeform
