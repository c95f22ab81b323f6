#include "Primitives/FaceSamples.h"

#include <cmath>
#include <limits>

namespace mlsdeform
{
FaceSamples faceSamples(const PointList& vertices, const std::vector<std::vector<int>>& faces)
{
  FaceSamples samples;
  const std::size_t n = faces.size();
  samples.barycenters.assign(n, Vec3::Zero());
  samples.normals.assign(n, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  samples.areas.assign(n, 0.0);
  for (std::size_t f = 0; f < n; ++f)
  {
    const std::vector<int>& face = faces[f];
    for (int v : face)
    {
      if (v < 0 || v >= static_cast<int>(vertices.size()))
      {
        throw InvalidInputException("face " + std::to_string(f) + " uses vertex " + std::to_string(v) + ", which does not exist");
      }
      if (!vertices[v].allFinite())
      {
        throw InvalidInputException("face " + std::to_string(f) + " uses a vertex with a NaN or infinite coordinate");
      }
    }
    if (face.empty())
    {
      continue;
    }
    // Newell's normal (twice the vector area) and the fan's area-weighted centroid
    Vec3 newell = Vec3::Zero(), centroid = Vec3::Zero(), mean = Vec3::Zero();
    double scale = 0, weight = 0;
    for (std::size_t a = 0; a < face.size(); ++a)
    {
      const Vec3& p = vertices[face[a]];
      const Vec3& q = vertices[face[(a + 1) % face.size()]];
      newell += p.cross(q);
      scale += (q - p).squaredNorm();
      mean += p;
    }
    mean /= static_cast<double>(face.size());
    for (std::size_t a = 1; a + 1 < face.size(); ++a)
    {
      const Vec3& p0 = vertices[face[0]];
      const Vec3& p1 = vertices[face[a]];
      const Vec3& p2 = vertices[face[a + 1]];
      const double w = (p1 - p0).cross(p2 - p0).dot(newell);
      centroid += w * (p0 + p1 + p2) / 3;
      weight += w;
    }
    const double area = newell.norm() / 2;
    if (face.size() < 3 || !(area > 1e-12 * scale))
    {
      samples.barycenters[f] = mean;
      continue;
    }
    samples.barycenters[f] = weight > 0 ? Vec3(centroid / weight) : mean;
    samples.normals[f] = newell.normalized();
    samples.areas[f] = area;
  }
  return samples;
}
} // namespace mlsdeform
