#include "Session/SlipPlanes.h"

#include "Vocabulary/RegionRoles.h"

#include <map>
#include <string>

using namespace mlsdeform;

namespace mlsvtk
{
std::vector<SlipPlane> slipPlanes(const std::vector<RegionInput>& regions)
{
  std::vector<SlipPlane> planes;
  for (std::size_t c = 0; c < regions.size(); ++c)
  {
    if (regions[c].role != roles::Slip)
    {
      continue;
    }
    // one plane per constraint set (a region of several patches selected by name: each its plane)
    const PointList& positions = regions[c].gathered.positions;
    const std::vector<int>& sets = regions[c].gathered.sets;
    std::map<int, PointList> bySet;
    for (std::size_t i = 0; i < positions.size(); ++i)
    {
      bySet[sets.empty() ? 0 : sets[i]].push_back(positions[i]);
    }
    for (const auto& [set, points] : bySet)
    {
      SlipPlane slip;
      slip.bounds = boundingBox(points);
      const double diagonal = slip.bounds.size().norm();
      slip.plane = fitPlane(points);
      if (points.size() < 3 || slip.plane.farthest > 1e-6 * diagonal)
      {
        throw InvalidInputException("Regions input #" + std::to_string(c) + " (Slip)" +
          (bySet.size() > 1 ? ", its block " + std::to_string(set) + "," : std::string()) +
          " is not a plane: its points lie up to " + std::to_string(slip.plane.farthest / diagonal) +
          " of their diagonal from their least-squares plane (at most 1e-6)");
      }
      slip.tolerance = slip.plane.farthest + 1e-9 * diagonal;
      slip.bounds.lower.array() -= slip.tolerance;
      slip.bounds.upper.array() += slip.tolerance;
      planes.push_back(slip);
    }
  }
  return planes;
}

namespace
{
// The slides of one point's displacement d (each the projection I - n n^T, symmetric: the
// transposed map is their product reversed).
void slidePoint(const std::vector<SlipPlane>& planes, const Vec3& x, double* d, bool transposed)
{
  for (std::size_t k = 0; k < planes.size(); ++k)
  {
    const SlipPlane& slip = planes[transposed ? planes.size() - 1 - k : k];
    if (slip.holds(x))
    {
      Eigen::Map<Vec3> displacement(d);
      displacement -= slip.plane.normal.dot(displacement) * slip.plane.normal;
    }
  }
}
}

void slideOnPlanes(const std::vector<SlipPlane>& planes, const PointList& points, long offset, long n, double* d, bool transposed)
{
  if (planes.empty())
  {
    return;
  }
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i)
  {
    slidePoint(planes, points[offset + i], d + 3 * i, transposed);
  }
}

void slideRowsOnPlanes(const std::vector<SlipPlane>& planes, const PointList& points, const std::vector<long>& rows, double* d, bool transposed)
{
  if (planes.empty())
  {
    return;
  }
#pragma omp parallel for schedule(static)
  for (long i = 0; i < static_cast<long>(rows.size()); ++i)
  {
    slidePoint(planes, points[rows[i]], d + 3 * i, transposed);
  }
}
} // namespace mlsvtk
