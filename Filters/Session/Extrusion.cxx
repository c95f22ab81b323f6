#include "Session/Extrusion.h"

#include <algorithm>
#include <limits>

using namespace mlsdeform;

namespace mlsvtk
{
const PointList& Extrusion::evaluated(const PointList& x, PointList& storage) const
{
  if (!active())
  {
    return x;
  }
  storage = x;
  for (Vec3& p : storage)
  {
    p[axis] = middle;
  }
  return storage;
}

SlipPlane Extrusion::slide() const
{
  SlipPlane slip;
  const double infinity = std::numeric_limits<double>::infinity();
  slip.plane.point = Vec3::Zero();
  slip.plane.point[axis] = middle;
  slip.plane.normal = Vec3::Unit(axis);
  slip.bounds.lower = Vec3::Constant(-infinity);
  slip.bounds.upper = Vec3::Constant(infinity);
  slip.tolerance = infinity;
  return slip;
}

bool Extrusion::normalPlane(const PointList& positions, double tolerance) const
{
  if (!active() || positions.empty())
  {
    return false;
  }
  const auto [low, high] = std::minmax_element(
    positions.begin(), positions.end(), [this](const Vec3& a, const Vec3& b) { return a[axis] < b[axis]; });
  return (*high)[axis] - (*low)[axis] <= tolerance;
}
} // namespace mlsvtk
