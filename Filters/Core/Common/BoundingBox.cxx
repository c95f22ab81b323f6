#include "Common/BoundingBox.h"

#include <limits>

namespace mlsdeform
{
BoundingBox boundingBox(const PointList& points)
{
  BoundingBox box;
  if (points.empty())
  {
    return box;
  }
  box.lower = box.upper = points.front();
  for (const Vec3& p : points)
  {
    box.lower = box.lower.cwiseMin(p);
    box.upper = box.upper.cwiseMax(p);
  }
  return box;
}

BoundingBox boundingBox(const BoundingBox* local, const Collective& group)
{
  // maxima of (-lower, upper): exact, the same on every process
  std::vector<double> extremes(6, -std::numeric_limits<double>::infinity());
  for (int c = 0; local && c < 3; ++c)
  {
    extremes[c] = -local->lower[c];
    extremes[3 + c] = local->upper[c];
  }
  group.maximum(extremes);
  BoundingBox box;
  for (int c = 0; c < 3; ++c)
  {
    box.lower[c] = -extremes[c];
    box.upper[c] = extremes[3 + c];
  }
  return box;
}

void requireFinite(const PointList& points, const char* what)
{
  for (const Vec3& p : points)
  {
    if (!p.allFinite())
    {
      throw InvalidInputException(std::string(what) + " contain NaN or infinite coordinates");
    }
  }
}
} // namespace mlsdeform
