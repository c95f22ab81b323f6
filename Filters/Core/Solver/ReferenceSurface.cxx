#include "Solver/ReferenceSurface.h"

#include "Common/BoundingBox.h"

#include <algorithm>
#include <array>

namespace mlsdeform
{
namespace
{
// The point of triangle (a, b, c) nearest to p: Ericson, "Real-Time Collision Detection" (2005),
// section 5.1.5, by the Voronoi regions of the corners, edges and face.
Vec3 nearestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0)
  {
    return a;
  }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3)
  {
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    return a + d1 / (d1 - d3) * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6)
  {
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    return a + d2 / (d2 - d6) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
  {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denominator = 1 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}
}

ReferenceSurface::ReferenceSurface(PointList corners)
{
  requireFinite(corners, "reference surface corners");
  using Triangle = std::array<double, 9>;
  std::vector<Triangle> triangles;
  for (std::size_t t = 0; t + 2 < corners.size(); t += 3)
  {
    const Vec3 normal = (corners[t + 1] - corners[t]).cross(corners[t + 2] - corners[t]);
    if (normal.norm() > 0)
    {
      Triangle triangle;
      for (int k = 0; k < 3; ++k)
      {
        std::copy(corners[t + k].data(), corners[t + k].data() + 3, triangle.data() + 3 * k);
      }
      triangles.push_back(triangle);
    }
  }
  if (triangles.empty())
  {
    throw InvalidInputException("the reference surface has no triangle of non-zero area");
  }
  std::sort(triangles.begin(), triangles.end());
  PointList centroids;
  std::vector<double> radii;
  for (const Triangle& triangle : triangles)
  {
    const Vec3 a(triangle.data()), b(triangle.data() + 3), c(triangle.data() + 6);
    Corners.insert(Corners.end(), { a, b, c });
    Normals.push_back((b - a).cross(c - a).normalized());
    const Vec3 centroid = (a + b + c) / 3;
    centroids.push_back(centroid);
    radii.push_back(std::max({ (a - centroid).norm(), (b - centroid).norm(), (c - centroid).norm() }));
  }
  Centroids.build(centroids);
  Centroids.setRadii(radii);
}

ReferenceSurface::Nearest ReferenceSurface::nearest(const Vec3& x) const
{
  const auto onTriangle = [&](int t) { return nearestOnTriangle(x, Corners[3 * t], Corners[3 * t + 1], Corners[3 * t + 2]); };
  const int t = Centroids.nearestObject(x, [&](int i) { return (onTriangle(i) - x).squaredNorm(); });
  const Vec3 point = onTriangle(t);
  return { point, Normals[t], (point - x).norm() };
}
} // namespace mlsdeform
