// Bounding boxes of point lists (on one process or over all of a group) and the check that
// coordinates are finite: what most of the core asks of a point list before it uses it.
#pragma once

#include "Common/Collective.h"
#include "Common/CoreTypes.h"

namespace mlsdeform
{
/// The axis-aligned bounding box of points (both corners zero for none).
struct BoundingBox
{
  Vec3 lower = Vec3::Zero(), upper = Vec3::Zero();
  Vec3 size() const { return upper - lower; }
};
BoundingBox boundingBox(const PointList& points);

/// The box around the boxes of all processes of group (local: this process's, or none).
BoundingBox boundingBox(const BoundingBox* local, const Collective& group);

/// The bounding box of the points of all processes of group.
inline BoundingBox boundingBox(const PointList& points, const Collective& group)
{
  const BoundingBox local = boundingBox(points);
  return boundingBox(points.empty() ? nullptr : &local, group);
}

/// The largest side of the points' bounding box (0 for none): the model's length l.
inline double largestSide(const PointList& points)
{
  return boundingBox(points).size().maxCoeff();
}

/// Throws InvalidInputException if a coordinate is NaN or infinite.
void requireFinite(const PointList& points, const char* what);
} // namespace mlsdeform
