// Section 6.2: every projection leaves data that satisfies its constraint unchanged and maps
// perturbed data onto the constraint set.
#include "../TestHarness.h"
#include "Solver/ConstraintProjections.h"
#include "TestGeometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

using namespace mlsdeform;
using testgeometry::maxDistance;

namespace
{
PointList perturbed(const PointList& x, double amount, unsigned seed)
{
  std::mt19937 random(seed);
  std::normal_distribution<double> normal(0, amount);
  PointList out = x;
  for (Vec3& p : out)
    p += Vec3(normal(random), normal(random), normal(random));
  return out;
}


const Eigen::Matrix3d Tilt = (Eigen::AngleAxisd(0.4, Vec3(1, 2, 0).normalized()) * Eigen::AngleAxisd(0.3, Vec3::UnitZ())).toRotationMatrix();
const Vec3 Offset(0.5, -1, 2);

// Points on the circle (or cylinder, with heights) of the given radius, tilted and offset, at
// random or (evenly) equally spaced angles.
PointList onCylinder(int count, double radius, double height, unsigned seed, bool evenly = false)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), h(0, height);
  PointList x;
  for (int i = 0; i < count; ++i)
  {
    const double a = evenly ? 2 * M_PI * i / count : angle(random);
    x.push_back(Tilt * Vec3(radius * std::cos(a), radius * std::sin(a), height > 0 ? h(random) : 0.0) + Offset);
  }
  return x;
}
}

// Two kinds of bound below. Data that satisfy a constraint are moved by round-off only: sums of
// n terms of size |x| (the coordinates are <= 5) round to n eps |x| (eps = 2.2e-16), times the
// condition of the fit. Noisy data (normal noise sigma per coordinate) give fits whose parameters
// scatter by sigma / sqrt(n) over the point spread; their bounds are a few such standard
// deviations, well below what the unprojected (noisy) data would show.

TEST(PlaneProjection)
{
  PointList x;
  std::mt19937 random(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i)
    x.push_back(Tilt * Vec3(u(random), u(random), 0) + Offset);
  // round-off: 200 terms x eps x |x| <= 3.5 = 1.6e-13 in the covariance; the normal (eigenvalue 0,
  // the others ~ 1/3) is as well conditioned as that
  std::printf("plane moved by %.2e\n", maxDistance(projectToPlane(x), x));
  CHECK(maxDistance(projectToPlane(x), x) < 1e-12);
  const PointList projected = projectToPlane(perturbed(x, 0.01, 2));
  CHECK(maxDistance(projectToPlane(projected), projected) < 1e-12); // on a plane now (round-off as above)
  const Vec3 normal = Tilt * Vec3::UnitZ();
  double offPlane = 0;
  for (const Vec3& p : projected)
    offPlane = std::max(offPlane, std::abs(normal.dot(p - projected[0])));
  // and that plane is close to the original one: each tilt component of the fitted normal has the
  // standard deviation sigma / (sqrt(n) x rms extent 0.58) = 1.2e-3 rad; 4 of them (4.9e-3 rad)
  // over the patch's diameter 2.83 is 0.014 < 2 sigma, while the unprojected points scatter by
  // ~4 sigma = 0.04
  std::printf("projected points off the original plane: %.2e\n", offPlane);
  CHECK(offPlane < 2 * 0.01);
}

TEST(CircleProjection)
{
  const PointList x = onCylinder(100, 0.7, 0, 3, true); // evenly spaced: the mean is the center
  // round-off: 100 terms x eps x |x| <= 3 = 6.7e-14 in the fit's sums; its 3 x 3 normal matrix
  // is well conditioned (entries ~ n r^2 / 2 and n); Gauss-Newton then steps by round-off only
  std::printf("circle moved by %.2e\n", maxDistance(projectToCircle(x), x));
  CHECK(maxDistance(projectToCircle(x), x) < 1e-12);
  const PointList projected = projectToCircle(perturbed(x, 0.01, 4));
  std::printf("projected circle moved by %.2e\n", maxDistance(projectToCircle(projected), projected));
  CHECK(maxDistance(projectToCircle(projected), projected) < 1e-12);
  // equidistant from the center, radius close to the original
  Vec3 center = Vec3::Zero();
  for (const Vec3& p : projected)
    center += p / projected.size();
  double minR = 1e9, maxR = 0;
  for (const Vec3& p : projected)
  {
    minR = std::min(minR, (p - center).norm());
    maxR = std::max(maxR, (p - center).norm());
  }
  std::printf("projected radius %.6f .. %.6f\n", minR, maxR);
  // The projection moves each point along the circle by its tangential noise, so the mean of the
  // projected points is off the fitted centre by ~sigma / sqrt(n) = 1e-3 (one standard
  // deviation), and the fitted radius is off 0.7 by the mean radial noise, also ~sigma / sqrt(n):
  // both bounds are sigma = 0.01, about 5 standard deviations of the offsets they add up, while
  // unprojected noisy points would spread in radius by ~5 sigma = 0.05.
  CHECK(maxR - minR < 0.01 && std::abs(maxR - 0.7) < 0.01);
}

TEST(CylinderProjection)
{
  const PointList x = onCylinder(400, 0.7, 2.0, 5);
  Vec3 axis = Vec3::Zero();
  // Exact data: the pattern search stops at the step 1e-10 rad, and its error function resolves far
  // finer steps (every term vanishes at the axis, up to eps |x|^2), so the axis is within a few
  // steps of the true one; that turns points |p - centre| <= 1.22 away by a few 1.2e-10.
  std::printf("cylinder moved by %.2e\n", maxDistance(projectToCylinder(x, axis), x));
  CHECK(maxDistance(projectToCylinder(x, axis), x) < 1e-9);
  const Vec3 trueAxis = Tilt * Vec3::UnitZ();
  const double angle = std::acos(std::min(1.0, std::abs(axis.dot(trueAxis)))) * 180 / M_PI;
  std::printf("fitted axis off by %.2e degrees\n", angle);
  // the angle is read through acos of a dot product k ulps below 1: sqrt(2 k eps) rad, 2.4e-6
  // degrees for k = 4 (the axis itself is ~1e-10 rad off); 1e-5 degrees allows k = 70
  CHECK(angle < 1e-5);
  // noisy data: projected onto a cylinder close to the original; the fit restarts from the axis
  Vec3 noisyAxis = Vec3::Zero();
  const PointList projected = projectToCylinder(perturbed(x, 0.01, 6), noisyAxis);
  Vec3 again = noisyAxis;
  std::printf("projected cylinder moved by %.2e, noisy axis off by %.3f degrees\n", maxDistance(projectToCylinder(projected, again), projected), std::acos(std::min(1.0, std::abs(noisyAxis.dot(trueAxis)))) * 180 / M_PI);
  CHECK(maxDistance(projectToCylinder(projected, again), projected) < 1e-9); // exact data, as above
  // The noise tilts the fitted axis: radial noise sigma at heights of standard deviation
  // 2 / sqrt(12) = 0.58 gives each tilt component a standard deviation sigma / (sqrt(n / 2) x 0.58)
  // = 1.2e-3 rad = 0.07 degrees; 0.5 degrees is 7 of them.
  CHECK(std::acos(std::min(1.0, std::abs(noisyAxis.dot(trueAxis)))) * 180 / M_PI < 0.5);
}

TEST(SimilarityAndRigidProjections)
{
  const PointList rest = onCylinder(50, 1.0, 1.0, 7);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.5, Vec3(0, 1, 1).normalized()).toRotationMatrix();
  PointList similar, rigid;
  for (const Vec3& p : rest)
  {
    similar.push_back(1.3 * R * p + Vec3(1, 2, 3));
    rigid.push_back(R * p + Vec3(1, 2, 3));
  }
  // round-off: the cross-covariance sums 50 terms of size |x| <= 5 (50 x eps x 5 = 5.5e-14), and
  // its SVD is well conditioned (the rest shape spans 3 dimensions about equally): 1e-12
  std::printf("similarity moved by %.2e, rigid by %.2e\n", maxDistance(projectToSimilarity(rest, similar), similar), maxDistance(projectToRigid(rest, rigid), rigid));
  CHECK(maxDistance(projectToSimilarity(rest, similar), similar) < 1e-12);
  CHECK(maxDistance(projectToRigid(rest, rigid), rigid) < 1e-12);
  // a scaled target: the rigid projection keeps every distance of the rest shape
  const PointList kept = projectToRigid(rest, similar);
  double distortion = 0;
  for (std::size_t i = 1; i < rest.size(); ++i)
    distortion = std::max(distortion, std::abs((kept[i] - kept[0]).norm() - (rest[i] - rest[0]).norm()));
  std::printf("distortion %.2e\n", distortion);
  CHECK(distortion < 1e-12); // a rotation of the rest shape: round-off as above
  // a noisy target: the similarity projection keeps every distance ratio
  const PointList shaped = projectToSimilarity(rest, perturbed(similar, 0.05, 8));
  const double scale = (shaped[1] - shaped[0]).norm() / (rest[1] - rest[0]).norm();
  double ratio = 0;
  for (std::size_t i = 2; i < rest.size(); ++i)
    ratio = std::max(ratio, std::abs((shaped[i] - shaped[0]).norm() - scale * (rest[i] - rest[0]).norm()));
  std::printf("ratio %.2e scale %.4f\n", ratio, scale);
  // ratios: round-off as above; the scale fitted to 50 points with noise sigma = 0.05 about the rms
  // radius 1.04 of the rest shape scatters by sigma / (sqrt(n) x 1.04) = 6.8e-3: 0.035 is 5 of that
  CHECK(ratio < 1e-12 && std::abs(scale - 1.3) < 0.035);
}

TEST(SymmetricProjection)
{
  // pairs of points mirrored in a tilted plane, and one point on it: the projection keeps a
  // symmetric displacement field, maps any field onto a symmetric one, is idempotent and
  // orthogonal (the residual is orthogonal to every symmetric field)
  Plane mirror;
  mirror.point = Offset;
  mirror.normal = Tilt * Vec3(0, 1, 0);
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity() - 2 * mirror.normal * mirror.normal.transpose();
  const auto reflect = [&](const Vec3& x) { return Vec3(mirror.point + R * (x - mirror.point)); };
  PointList rest = perturbed(PointList(20, Offset), 1.0, 7);
  const std::size_t half = rest.size();
  for (std::size_t i = 0; i < half; ++i)
    rest.push_back(reflect(rest[i]));
  rest.push_back(mirror.project(Offset + Vec3(0.3, 0.2, 0.1)));
  const std::vector<int> partner = mirrorPartners(rest, mirror, 1e-9);
  CHECK(std::count(partner.begin(), partner.end(), -1) == 0);
  for (std::size_t i = 0; i < rest.size(); ++i)
    CHECK(partner[partner[i]] == static_cast<int>(i));
  CHECK(partner.back() == static_cast<int>(rest.size()) - 1);

  const PointList moved = perturbed(rest, 0.1, 8);
  const PointList projected = projectToSymmetric(rest, moved, partner, mirror);
  double asymmetry = 0;
  for (std::size_t i = 0; i < rest.size(); ++i)
    asymmetry = std::max(asymmetry, ((projected[i] - rest[i]) - R * (projected[partner[i]] - rest[partner[i]])).norm());
  CHECK(asymmetry <= 1e-14);
  CHECK(maxDistance(projectToSymmetric(rest, projected, partner, mirror), projected) <= 1e-14);
  // orthogonal: (moved - projected) . (s - rest) = 0 for the symmetric field s = projected
  double inner = 0, scale = 0;
  for (std::size_t i = 0; i < rest.size(); ++i)
  {
    inner += (moved[i] - projected[i]).dot(projected[i] - rest[i]);
    scale += (moved[i] - projected[i]).norm() * (projected[i] - rest[i]).norm();
  }
  CHECK(std::abs(inner) <= 1e-12 * scale);
  // a point without its image
  rest.push_back(Offset + Tilt * Vec3(0, 3, 0));
  const std::vector<int> missing = mirrorPartners(rest, mirror, 1e-9);
  CHECK(missing.back() == -1);
}

TEST(DistanceTranslation)
{
  // two sets of 4 and 12 points: after the translations their centroids are at the asked distance,
  // the smaller set moved three times as far; along an axis only that component counts
  const PointList a = perturbed(PointList(4, Vec3(0, 0, 0)), 0.1, 1);
  const PointList b = perturbed(PointList(12, Vec3(2, 1, 0)), 0.1, 2);
  for (const Vec3 axis : { Vec3(0, 0, 0), Vec3(1, 0, 0) })
  {
    const Vec3 ta = distanceTranslation(a, b, axis, 1.5);
    const Vec3 tb = -ta * 4.0 / 12.0;
    const Vec3 e = centroid(b) + tb - centroid(a) - ta;
    CHECK_NEAR(axis.squaredNorm() > 0 ? e.dot(axis) : e.norm(), 1.5, 1e-14);
    CHECK_NEAR(ta.norm(), 3 * tb.norm(), 1e-14);
    const Vec3 kept = distanceTranslation(perturbed(a, 0, 3), b, axis, axis.squaredNorm() > 0 ? (centroid(b) - centroid(a)).dot(axis)
                                                                                        : (centroid(b) - centroid(a)).norm());
    CHECK(kept.norm() <= 1e-14);
  }
}

namespace
{
// The closed surface of the unit cube [0, 1]^3, two outward triangles per face, in shuffled order.
PointList cubeTriangles(unsigned seed)
{
  std::vector<std::array<Vec3, 3>> triangles;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
    {
      const Vec3 n = (side ? 1.0 : -1.0) * Vec3::Unit(axis);
      const Vec3 u = Vec3::Unit((axis + 1) % 3), v = Vec3::Unit((axis + 2) % 3);
      const Vec3 o = side * Vec3::Unit(axis);
      Vec3 c[4] = { o, o + u, o + u + v, o + v };
      if (u.cross(v).dot(n) < 0)
        std::swap(c[1], c[3]);
      triangles.push_back({ c[0], c[1], c[2] });
      triangles.push_back({ c[0], c[2], c[3] });
    }
  std::shuffle(triangles.begin(), triangles.end(), std::mt19937(seed));
  PointList corners;
  for (const auto& t : triangles)
    corners.insert(corners.end(), t.begin(), t.end());
  return corners;
}

// The distance from x to the cube's surface, in closed form.
double distanceToCube(const Vec3& x)
{
  const Vec3 outside = (x - Vec3::Ones()).cwiseMax(-x).cwiseMax(0.0);
  if (outside.squaredNorm() > 0)
    return outside.norm();
  return std::min(x.minCoeff(), (Vec3::Ones() - x).minCoeff());
}
}

TEST(ReferenceSurfaceNearestPoint)
{
  // against the closed form on points inside, outside and near edges and corners; the same in
  // any order of the triangles
  const ReferenceSurface surface(cubeTriangles(1)), shuffled(cubeTriangles(2));
  CHECK(surface.triangles() == 12);
  std::mt19937 random(4);
  std::uniform_real_distribution<double> uniform(-0.5, 1.5);
  for (int i = 0; i < 2000; ++i)
  {
    const Vec3 x(uniform(random), uniform(random), uniform(random));
    const ReferenceSurface::Nearest q = surface.nearest(x);
    CHECK_NEAR(q.distance, distanceToCube(x), 1e-14);
    CHECK_NEAR(distanceToCube(q.point), 0, 1e-14);
    CHECK(shuffled.nearest(x).point == q.point);
  }
}

TEST(ReferenceSurfaceRefusesBadTriangles)
{
  CHECK_THROWS(ReferenceSurface{ PointList(6, Vec3(1, 2, 3)) }, InvalidInputException); // zero area
  PointList corners = cubeTriangles(1);
  corners[5].x() = std::nan("");
  CHECK_THROWS(ReferenceSurface{ corners }, InvalidInputException);
}

TEST(OffsetProjection)
{
  // points outside the cube (side +1): those nearer than 0.2 go to 0.2 along their direction from
  // the surface, those that crossed into it back out along the face normal, the others stay
  const ReferenceSurface cube(cubeTriangles(1));
  const PointList x{ Vec3(0.5, 0.5, 1.3), Vec3(0.5, 0.5, 1.1), Vec3(0.5, 0.5, 0.95), Vec3(1.1, 1.1, 0.5) };
  const PointList y = projectOutside(cube, x, std::vector<double>(4, 1.0), 0.2);
  CHECK(y[0] == x[0]);
  CHECK_NEAR((y[1] - Vec3(0.5, 0.5, 1.2)).norm(), 0, 1e-15);
  CHECK_NEAR((y[2] - Vec3(0.5, 0.5, 1.2)).norm(), 0, 1e-15);
  CHECK_NEAR(distanceToCube(y[3]), 0.2, 1e-15);
  CHECK_NEAR((y[3] - Vec3(1, 1, 0.5)).normalized().dot(Vec3(1, 1, 0).normalized()), 1, 1e-15);
  // a point inside that must stay inside (side -1) is kept 0.2 from the walls
  const PointList inside = projectOutside(cube, { Vec3(0.5, 0.5, 0.9) }, { -1.0 }, 0.2);
  CHECK_NEAR((inside[0] - Vec3(0.5, 0.5, 0.8)).norm(), 0, 1e-15);
}

TEST_MAIN
