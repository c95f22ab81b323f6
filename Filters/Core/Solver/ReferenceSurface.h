// The fixed reference surface of an Offset constraint (the inner part that an outer skin must
// keep its distance from: a minimum wall thickness): triangles, and for a position the nearest
// point of the surface with the normal of its triangle.
#pragma once

#include "Common/KdTree.h"

namespace mlsdeform
{
class ReferenceSurface
{
public:
  /// corners: three per triangle. The triangles are put into a canonical order (the same surface
  /// however it was split over processes) and those of zero area dropped; throws
  /// InvalidInputException when none is left or a corner is not finite.
  explicit ReferenceSurface(PointList corners);

  struct Nearest
  {
    Vec3 point;      // the surface's point nearest to the position
    Vec3 normal;     // the unit normal of its triangle (by the corners' order)
    double distance; // from the position
  };
  Nearest nearest(const Vec3& x) const;

  std::size_t triangles() const { return Normals.size(); }

private:
  PointList Corners; // three per triangle
  std::vector<Vec3> Normals;
  KdTree Centroids; // each triangle in the ball around its centroid through its farthest corner
};
} // namespace mlsdeform
