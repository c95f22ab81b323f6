// CAD-like parts with known primitives for the primitive detection tests and benchmark (paper
// section 6.3): patches of planes, cylinders, spheres and cones, each face labelled with the
// primitive it was generated on. Faces are triangles of parametric grids; a patch keeps the
// faces whose centroid passes a test (a plate with holes). Patches do not share vertices, so
// noise never moves a vertex off its own primitive's neighbourhood.
#pragma once

#include "Primitives/Primitives.h"

#include <array>
#include <cmath>
#include <functional>
#include <random>

namespace syntheticparts
{
using mlsdeform::PointList;
using mlsdeform::Primitive;
using mlsdeform::PrimitiveType;
using mlsdeform::Vec3;

struct Part
{
  PointList points;
  std::vector<std::vector<int>> faces;
  std::vector<int> truth;            // per face: its index in primitives
  std::vector<Primitive> primitives; // the exact surfaces the faces were generated on
  double diagonal() const
  {
    Vec3 lower = points[0], upper = points[0];
    for (const Vec3& p : points)
    {
      lower = lower.cwiseMin(p);
      upper = upper.cwiseMax(p);
    }
    return (upper - lower).norm();
  }
};

/// Adds the nu x nv grid of f over [0,1]^2 (two triangles per cell), keeping the triangles
/// whose centroid passes keep, as faces of a new primitive.
inline void addPatch(Part& part, const Primitive& primitive, int nu, int nv, const std::function<Vec3(double, double)>& f,
  const std::function<bool(const Vec3&)>& keep = nullptr)
{
  const int label = static_cast<int>(part.primitives.size());
  part.primitives.push_back(primitive);
  const int base = static_cast<int>(part.points.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i)
      part.points.push_back(f(static_cast<double>(i) / nu, static_cast<double>(j) / nv));
  auto id = [&](int i, int j) { return base + j * (nu + 1) + i; };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      for (const std::array<int, 3>& t : { std::array<int, 3>{ id(i, j), id(i + 1, j), id(i + 1, j + 1) },
             std::array<int, 3>{ id(i, j), id(i + 1, j + 1), id(i, j + 1) } })
      {
        const Vec3 centroid = (part.points[t[0]] + part.points[t[1]] + part.points[t[2]]) / 3;
        if (keep && !keep(centroid))
          continue;
        part.faces.push_back({ t[0], t[1], t[2] });
        part.truth.push_back(label);
      }
}

inline Primitive plane(const Vec3& normal, const Vec3& point)
{
  Primitive p;
  p.type = PrimitiveType::Plane;
  p.axis = normal.normalized();
  p.offset = p.axis.dot(point);
  return p;
}

/// A rectangle origin + u s + v t, s, t in [0,1], with cells of about h.
inline void addRectangle(Part& part, const Vec3& origin, const Vec3& u, const Vec3& v, double h,
  const std::function<bool(const Vec3&)>& keep = nullptr)
{
  addPatch(part, plane(u.cross(v), origin), std::max(1, static_cast<int>(std::round(u.norm() / h))),
    std::max(1, static_cast<int>(std::round(v.norm() / h))), [=](double s, double t) { return Vec3(origin + s * u + t * v); }, keep);
}

/// The cylinder of the given axis (unit) through center, radius r, heights [z0, z1] along the
/// axis, angles [0, 2 pi) in n segments.
inline void addCylinder(Part& part, const Vec3& center, const Vec3& axis, double r, double z0, double z1, int n, double h)
{
  Primitive p;
  p.type = PrimitiveType::Cylinder;
  p.axis = axis.normalized();
  p.center = center;
  p.radius = r;
  const Vec3 e1 = (std::abs(p.axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(p.axis).normalized(), e2 = p.axis.cross(e1);
  addPatch(part, p, n, std::max(1, static_cast<int>(std::round((z1 - z0) / h))), [=](double s, double t) {
    const double a = 2 * M_PI * s;
    return Vec3(center + r * (std::cos(a) * e1 + std::sin(a) * e2) + (z0 + t * (z1 - z0)) * p.axis);
  });
}

/// The sphere zone between latitudes lat0 and lat1 (radians, about the z axis).
inline void addSphere(Part& part, const Vec3& center, double r, double lat0, double lat1, int n)
{
  Primitive p;
  p.type = PrimitiveType::Sphere;
  p.center = center;
  p.radius = r;
  addPatch(part, p, n, std::max(1, static_cast<int>(std::round(n * (lat1 - lat0) / (2 * M_PI)))), [=](double s, double t) {
    const double a = 2 * M_PI * s, b = lat0 + t * (lat1 - lat0);
    return Vec3(center + r * Vec3(std::cos(b) * std::cos(a), std::cos(b) * std::sin(a), std::sin(b)));
  });
}

/// The cone of the given apex, unit axis (into the opening) and half angle between the
/// distances h0 and h1 from the apex along the axis.
inline void addCone(Part& part, const Vec3& apex, const Vec3& axis, double angle, double h0, double h1, int n, double h)
{
  Primitive p;
  p.type = PrimitiveType::Cone;
  p.center = apex;
  p.axis = axis.normalized();
  p.setAngle(angle);
  const Vec3 e1 = (std::abs(p.axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(p.axis).normalized(), e2 = p.axis.cross(e1);
  const double slant = (h1 - h0) / std::cos(angle);
  addPatch(part, p, n, std::max(1, static_cast<int>(std::round(slant / h))), [=](double s, double t) {
    const double a = 2 * M_PI * s, height = h0 + t * (h1 - h0);
    return Vec3(apex + height * p.axis + height * std::tan(angle) * (std::cos(a) * e1 + std::sin(a) * e2));
  });
}

/// A block [0,4] x [0,3] x [0,1] (cells of about h) with a through hole, a cylindrical boss
/// with a flat top, a spherical dome and a conical spike on its top face: 6 + 2 + 1 + 1 + 1
/// primitives, 9 planes counted with the boss's top. n: segments around the round features.
inline Part blockWithFeatures(double h, int n)
{
  Part part;
  const Vec3 hole(0.8, 0.8, 0), boss(3.0, 0.9, 0), dome(1.1, 2.1, 0), spike(3.0, 2.2, 0);
  const double holeRadius = 0.4, bossRadius = 0.5, domeRadius = 0.6, spikeRadius = 0.45, spikeHeight = 0.7;
  auto outside = [](const Vec3& c, double r) { return [=](const Vec3& x) { return std::hypot(x.x() - c.x(), x.y() - c.y()) > r; }; };
  auto topKeep = [=](const Vec3& x) {
    return outside(hole, holeRadius)(x) && outside(boss, bossRadius)(x) && outside(dome, domeRadius)(x) && outside(spike, spikeRadius)(x);
  };
  addRectangle(part, Vec3(0, 0, 1), Vec3(4, 0, 0), Vec3(0, 3, 0), h, topKeep);
  addRectangle(part, Vec3(0, 0, 0), Vec3(0, 3, 0), Vec3(4, 0, 0), h, outside(hole, holeRadius));
  addRectangle(part, Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 0, 1), h);
  addRectangle(part, Vec3(0, 3, 0), Vec3(0, 0, 1), Vec3(4, 0, 0), h);
  addRectangle(part, Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 3, 0), h);
  addRectangle(part, Vec3(4, 0, 0), Vec3(0, 3, 0), Vec3(0, 0, 1), h);
  addCylinder(part, hole, Vec3::UnitZ(), holeRadius, 0, 1, n, h);
  addCylinder(part, boss, Vec3::UnitZ(), bossRadius, 1, 1.8, n, h);
  addRectangle(part, Vec3(boss.x() - bossRadius, boss.y() - bossRadius, 1.8), Vec3(2 * bossRadius, 0, 0), Vec3(0, 2 * bossRadius, 0),
    h / 2, [=](const Vec3& x) { return !outside(boss, bossRadius)(x); });
  addSphere(part, Vec3(dome.x(), dome.y(), 1), domeRadius, 0, 80 * M_PI / 180, n);
  addCone(part, Vec3(spike.x(), spike.y(), 1 + spikeHeight), -Vec3::UnitZ(), std::atan(spikeRadius / spikeHeight), 0.05, spikeHeight, n, h);
  return part;
}

/// The part of separate primitives (no face of one touches another): the six faces of a box
/// [0,2] x [0,1.5] x [0,1], an open cylinder, a sphere zone (latitudes -50 to 50 degrees) and an
/// open cone, side by side along x (diagonal about 7.9). Triangles have legs of at least h: the
/// round patches get as many segments as keep their narrowest cells (the sphere's at 50 degrees
/// latitude, the cone's small end) at least h wide.
inline Part separatePrimitives(double h)
{
  Part part;
  addRectangle(part, Vec3(0, 0, 0), Vec3(0, 1.5, 0), Vec3(2, 0, 0), h);
  addRectangle(part, Vec3(0, 0, 1), Vec3(2, 0, 0), Vec3(0, 1.5, 0), h);
  addRectangle(part, Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 0, 1), h);
  addRectangle(part, Vec3(0, 1.5, 0), Vec3(0, 0, 1), Vec3(2, 0, 0), h);
  addRectangle(part, Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1.5, 0), h);
  addRectangle(part, Vec3(2, 0, 0), Vec3(0, 1.5, 0), Vec3(0, 0, 1), h);
  auto segments = [&](double radius) { return std::max(3, static_cast<int>(std::floor(2 * M_PI * radius / h))); };
  addCylinder(part, Vec3(3.2, 0.75, 0), Vec3::UnitZ(), 0.5, 0, 1.2, segments(0.5), h);
  const double latitude = 50 * M_PI / 180;
  addSphere(part, Vec3(4.9, 0.75, 0.6), 0.6, -latitude, latitude, segments(0.6 * std::cos(latitude)));
  const double angle = 30 * M_PI / 180, near = 0.6, far = 1.4;
  addCone(part, Vec3(6.8, 0.75, 1.4), -Vec3::UnitZ(), angle, near, far, segments(near * std::tan(angle)), h);
  return part;
}

/// Moves every vertex by Gaussian noise of standard deviation sigma per coordinate.
inline void addNoise(Part& part, double sigma, unsigned seed)
{
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0, sigma);
  for (Vec3& p : part.points)
    p += Vec3(noise(random), noise(random), noise(random));
}
} // namespace syntheticparts
