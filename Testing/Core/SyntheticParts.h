// CAD-like parts with known primitives for the primitive detection tests and benchmark (paper
// section 6.3): patches of planes, cylinders, spheres and cones, each face labelled with the
// primitive it was generated on. Faces are triangles of parametric grids; a patch keeps the
// faces whose centroid passes a test (a plate with holes). Patches do not share vertices, so
// noise never moves a vertex off its own primitive's neighbourhood, unless weld joins the
// coincident ones: then a grid's seam closes, a row of it collapsed to a point (a sphere's pole,
// a cone's apex, a disk's center) becomes a fan of triangles, and a cap shares its rim, as
// meshes are usually made (usualPrimitives). A part can also be turned (rotate) and refined
// (subdivide).
#pragma once

#include "Primitives/Primitives.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
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

/// The unit direction at angle 2 pi s around the unit axis (the same for every round patch of
/// that axis: a cap and its cylinder or cone meet at the same points).
inline Vec3 around(const Vec3& axis, double s)
{
  const Vec3 e1 = (std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(axis).normalized(), e2 = axis.cross(e1);
  return std::cos(2 * M_PI * s) * e1 + std::sin(2 * M_PI * s) * e2;
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
  addPatch(part, p, n, std::max(1, static_cast<int>(std::round((z1 - z0) / h))),
    [=](double s, double t) { return Vec3(center + r * around(p.axis, s) + (z0 + t * (z1 - z0)) * p.axis); });
}

/// The disk of the given center, unit axis (its normal) and radius r in n segments and rings of
/// about h; the innermost ring collapses to the center (a fan once welded).
inline void addDisk(Part& part, const Vec3& center, const Vec3& axis, double r, int n, double h)
{
  addPatch(part, plane(axis, center), n, std::max(1, static_cast<int>(std::round(r / h))),
    [=](double s, double t) { return Vec3(center + t * r * around(axis.normalized(), s)); });
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
  const double slant = (h1 - h0) / std::cos(angle);
  addPatch(part, p, n, std::max(1, static_cast<int>(std::round(slant / h))), [=](double s, double t) {
    const double height = h0 + t * (h1 - h0);
    return Vec3(apex + height * p.axis + height * std::tan(angle) * around(p.axis, s));
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

/// The six faces of the box [0,2] x [0,1.5] x [0,1] (cells of about h), separate rectangles.
inline void addBox(Part& part, double h)
{
  addRectangle(part, Vec3(0, 0, 0), Vec3(0, 1.5, 0), Vec3(2, 0, 0), h);
  addRectangle(part, Vec3(0, 0, 1), Vec3(2, 0, 0), Vec3(0, 1.5, 0), h);
  addRectangle(part, Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 0, 1), h);
  addRectangle(part, Vec3(0, 1.5, 0), Vec3(0, 0, 1), Vec3(2, 0, 0), h);
  addRectangle(part, Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1.5, 0), h);
  addRectangle(part, Vec3(2, 0, 0), Vec3(0, 1.5, 0), Vec3(0, 0, 1), h);
}

/// As many segments around a circle of the given radius as keep them at least h long.
inline int segments(double radius, double h)
{
  return std::max(3, static_cast<int>(std::floor(2 * M_PI * radius / h)));
}

/// The part of separate primitives (no face of one touches another): the six faces of a box
/// [0,2] x [0,1.5] x [0,1], an open cylinder, a sphere zone (latitudes -50 to 50 degrees) and an
/// open cone, side by side along x (diagonal about 7.9). Triangles have legs of at least h: the
/// round patches get as many segments as keep their narrowest cells (the sphere's at 50 degrees
/// latitude, the cone's small end) at least h wide.
inline Part separatePrimitives(double h)
{
  Part part;
  addBox(part, h);
  addCylinder(part, Vec3(3.2, 0.75, 0), Vec3::UnitZ(), 0.5, 0, 1.2, segments(0.5, h), h);
  const double latitude = 50 * M_PI / 180;
  addSphere(part, Vec3(4.9, 0.75, 0.6), 0.6, -latitude, latitude, segments(0.6 * std::cos(latitude), h));
  const double angle = 30 * M_PI / 180, near = 0.6, far = 1.4;
  addCone(part, Vec3(6.8, 0.75, 1.4), -Vec3::UnitZ(), angle, near, far, segments(near * std::tan(angle), h), h);
  return part;
}

/// Merges the vertices that coincide (within 1e-9 of the diagonal: the round-off of the
/// generators) and drops the faces left with fewer than three distinct vertices: a grid's seam
/// closes, a row collapsed to a point becomes a fan (of each cell's two triangles there, one
/// degenerates), a cap and its cylinder or cone share their rim. Unused vertices go.
inline void weld(Part& part)
{
  const double tolerance = 1e-9 * part.diagonal();
  using Cell = std::array<long long, 3>;
  auto cellOf = [&](const Vec3& p) {
    return Cell{ static_cast<long long>(std::floor(p.x() / tolerance)), static_cast<long long>(std::floor(p.y() / tolerance)),
      static_cast<long long>(std::floor(p.z() / tolerance)) };
  };
  std::map<Cell, std::vector<int>> cells; // the kept vertices by cell of the tolerance's size
  PointList kept;
  std::vector<int> index(part.points.size());
  for (std::size_t v = 0; v < part.points.size(); ++v)
  {
    const Vec3& p = part.points[v];
    const Cell c = cellOf(p);
    int same = -1;
    for (long long dx = -1; dx <= 1 && same < 0; ++dx)
      for (long long dy = -1; dy <= 1 && same < 0; ++dy)
        for (long long dz = -1; dz <= 1 && same < 0; ++dz)
        {
          const auto found = cells.find(Cell{ c[0] + dx, c[1] + dy, c[2] + dz });
          if (found != cells.end())
            for (int k : found->second)
              if ((kept[k] - p).norm() <= tolerance)
                same = k;
        }
    if (same < 0)
    {
      same = static_cast<int>(kept.size());
      kept.push_back(p);
      cells[c].push_back(same);
    }
    index[v] = same;
  }
  std::vector<std::vector<int>> faces;
  std::vector<int> truth;
  std::vector<int> used(kept.size(), -1);
  PointList points;
  for (std::size_t f = 0; f < part.faces.size(); ++f)
  {
    std::vector<int> face;
    for (int v : part.faces[f])
      if (std::find(face.begin(), face.end(), index[v]) == face.end())
        face.push_back(index[v]);
    if (face.size() < 3)
      continue;
    for (int& v : face)
    {
      if (used[v] < 0)
      {
        used[v] = static_cast<int>(points.size());
        points.push_back(kept[v]);
      }
      v = used[v];
    }
    faces.push_back(face);
    truth.push_back(part.truth[f]);
  }
  part.points = std::move(points);
  part.faces = std::move(faces);
  part.truth = std::move(truth);
}

/// The box, cylinder, sphere and cone of separatePrimitives meshed the usual way (weld): the
/// cylinder's seam closed; a full UV sphere of n segments and n / 2 rows (n as many as keep the
/// equator's segments at least h long), fans at its poles; the cone from its apex (a fan there,
/// 30 degrees, base radius 0.81), rows of about h. caps: the cylinder's ends and the cone's base
/// are disks (planes) that share their rims, fans at their centers. Diagonal about 7.9.
inline Part usualPrimitives(double h, bool caps)
{
  Part part;
  addBox(part, h);
  const Vec3 cylinder(3.2, 0.75, 0), apex(6.8, 0.75, 1.4);
  const double cylinderRadius = 0.5, cylinderHeight = 1.2, angle = 30 * M_PI / 180, coneHeight = 1.4;
  const double coneRadius = coneHeight * std::tan(angle);
  addCylinder(part, cylinder, Vec3::UnitZ(), cylinderRadius, 0, cylinderHeight, segments(cylinderRadius, h), h);
  addSphere(part, Vec3(4.9, 0.75, 0.6), 0.6, -M_PI / 2, M_PI / 2, segments(0.6, h));
  addCone(part, apex, -Vec3::UnitZ(), angle, 0, coneHeight, segments(coneRadius, h), h);
  if (caps)
  {
    addDisk(part, cylinder, Vec3::UnitZ(), cylinderRadius, segments(cylinderRadius, h), h);
    addDisk(part, cylinder + cylinderHeight * Vec3::UnitZ(), Vec3::UnitZ(), cylinderRadius, segments(cylinderRadius, h), h);
    addDisk(part, apex - coneHeight * Vec3::UnitZ(), -Vec3::UnitZ(), coneRadius, segments(coneRadius, h), h);
  }
  weld(part);
  return part;
}

/// Turns the part (its vertices and primitives) by the rotation about the origin.
inline void rotate(Part& part, const Eigen::Matrix3d& rotation)
{
  for (Vec3& p : part.points)
    p = rotation * p;
  for (Primitive& primitive : part.primitives)
  {
    primitive.axis = rotation * primitive.axis; // a plane's offset stays: (R n) . (R x) = n . x
    primitive.center = rotation * primitive.center;
  }
}

/// The point of the primitive's surface closest to x.
inline Vec3 closestOn(const Primitive& primitive, const Vec3& x)
{
  Vec3 normal;
  const double distance = primitive.distance(x, normal);
  const Vec3 inward = x - distance * normal, outward = x + distance * normal;
  return primitive.distance(inward) <= primitive.distance(outward) ? inward : outward;
}

/// Midpoint subdivision: each triangle becomes four, through the midpoints of its edges, which
/// move onto the primitive of the faces beside the edge (an edge between two primitives keeps
/// its midpoint). The faces keep their primitive.
inline void subdivide(Part& part)
{
  std::map<std::pair<int, int>, int> edgeTruth; // -1: faces of two primitives beside it
  auto edge = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for (std::size_t f = 0; f < part.faces.size(); ++f)
    for (std::size_t a = 0; a < 3; ++a)
    {
      const auto [entry, inserted] = edgeTruth.emplace(edge(part.faces[f][a], part.faces[f][(a + 1) % 3]), part.truth[f]);
      if (!inserted && entry->second != part.truth[f])
        entry->second = -1;
    }
  std::map<std::pair<int, int>, int> midpoint;
  for (const auto& [e, truth] : edgeTruth)
  {
    const Vec3 middle = (part.points[e.first] + part.points[e.second]) / 2;
    midpoint[e] = static_cast<int>(part.points.size());
    part.points.push_back(truth >= 0 ? closestOn(part.primitives[truth], middle) : middle);
  }
  std::vector<std::vector<int>> faces;
  std::vector<int> truth;
  for (std::size_t f = 0; f < part.faces.size(); ++f)
  {
    const std::vector<int>& t = part.faces[f];
    const int m01 = midpoint[edge(t[0], t[1])], m12 = midpoint[edge(t[1], t[2])], m20 = midpoint[edge(t[2], t[0])];
    for (const std::vector<int>& face : { std::vector<int>{ t[0], m01, m20 }, std::vector<int>{ m01, t[1], m12 },
           std::vector<int>{ m20, m12, t[2] }, std::vector<int>{ m01, m12, m20 } })
    {
      faces.push_back(face);
      truth.push_back(part.truth[f]);
    }
  }
  part.faces = std::move(faces);
  part.truth = std::move(truth);
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
