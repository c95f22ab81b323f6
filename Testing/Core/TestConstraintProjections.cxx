// Section 6.2: every projection leaves data that satisfies its constraint unchanged and maps
// perturbed data onto the constraint set.
#include "../TestHarness.h"
#include "ConstraintProjections.h"
#include "TestGeometry.h"

#include <Eigen/Geometry>

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

TEST(PlaneProjection)
{
  PointList x;
  std::mt19937 random(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i)
    x.push_back(Tilt * Vec3(u(random), u(random), 0) + Offset);
  CHECK(maxDistance(projectToPlane(x), x) < 1e-12);
  const PointList projected = projectToPlane(perturbed(x, 0.01, 2));
  CHECK(maxDistance(projectToPlane(projected), projected) < 1e-12); // on a plane now
  const Vec3 normal = Tilt * Vec3::UnitZ();
  double offPlane = 0;
  for (const Vec3& p : projected)
    offPlane = std::max(offPlane, std::abs(normal.dot(p - projected[0])));
  CHECK(offPlane < 0.01); // and that plane is close to the original one
}

TEST(CircleProjection)
{
  const PointList x = onCylinder(100, 0.7, 0, 3, true); // evenly spaced: the mean is the center
  CHECK(maxDistance(projectToCircle(x), x) < 1e-9);
  const PointList projected = projectToCircle(perturbed(x, 0.01, 4));
  CHECK(maxDistance(projectToCircle(projected), projected) < 1e-9);
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
  CHECK(maxR - minR < 0.05 && std::abs(maxR - 0.7) < 0.02);
}

TEST(CylinderProjection)
{
  const PointList x = onCylinder(400, 0.7, 2.0, 5);
  Vec3 axis = Vec3::Zero();
  // the axis minimizes a squared error: it is found to about sqrt(machine epsilon)
  CHECK(maxDistance(projectToCylinder(x, axis), x) < 1e-6);
  const Vec3 trueAxis = Tilt * Vec3::UnitZ();
  const double angle = std::acos(std::min(1.0, std::abs(axis.dot(trueAxis)))) * 180 / M_PI;
  std::printf("fitted axis off by %.2e degrees\n", angle);
  CHECK(angle < 1e-4);
  // noisy data: projected onto a cylinder close to the original; the fit restarts from the axis
  Vec3 noisyAxis = Vec3::Zero();
  const PointList projected = projectToCylinder(perturbed(x, 0.01, 6), noisyAxis);
  Vec3 again = noisyAxis;
  CHECK(maxDistance(projectToCylinder(projected, again), projected) < 1e-6);
  CHECK(std::acos(std::min(1.0, std::abs(noisyAxis.dot(trueAxis)))) * 180 / M_PI < 1.0);
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
  CHECK(maxDistance(projectToSimilarity(rest, similar), similar) < 1e-10);
  CHECK(maxDistance(projectToRigid(rest, rigid), rigid) < 1e-10);
  // a scaled target: the rigid projection keeps every distance of the rest shape
  const PointList kept = projectToRigid(rest, similar);
  double distortion = 0;
  for (std::size_t i = 1; i < rest.size(); ++i)
    distortion = std::max(distortion, std::abs((kept[i] - kept[0]).norm() - (rest[i] - rest[0]).norm()));
  CHECK(distortion < 1e-10);
  // a noisy target: the similarity projection keeps every distance ratio
  const PointList shaped = projectToSimilarity(rest, perturbed(similar, 0.05, 8));
  const double scale = (shaped[1] - shaped[0]).norm() / (rest[1] - rest[0]).norm();
  double ratio = 0;
  for (std::size_t i = 2; i < rest.size(); ++i)
    ratio = std::max(ratio, std::abs((shaped[i] - shaped[0]).norm() - scale * (rest[i] - rest[0]).norm()));
  CHECK(ratio < 1e-10 && std::abs(scale - 1.3) < 0.05);
}

TEST_MAIN
