// Z-order (Morton) sorting of points: consecutive points in that order are near each other, so a
// group of them can share one spatial search.
#pragma once

#include "Common/CoreTypes.h"

#include <algorithm>
#include <cstdint>

namespace mlsdeform
{
/// The Morton code of a cell: the 21 low bits of its coordinates interleaved (x lowest).
std::uint64_t mortonCode(std::uint64_t x, std::uint64_t y, std::uint64_t z);

/// The indices first..last-1 of points sorted along the Z-order curve of their bounding box
/// (2^21 cells per axis; ties by index).
std::vector<int> zOrder(const PointList& points, long first, long last);

/// The bounding box [lower, upper] of points[*begin], ..., points[*(end - 1)] (begin < end).
inline void boundingBoxOf(const PointList& points, const int* begin, const int* end, Vec3& lower, Vec3& upper)
{
  lower = upper = points[*begin];
  for (const int* i = begin + 1; i < end; ++i)
  {
    lower = lower.cwiseMin(points[*i]);
    upper = upper.cwiseMax(points[*i]);
  }
}

/// Calls visit(begin, end, lower, upper) for each group of up to size consecutive indices
/// [begin, end) of zOrder(points, first, last), with the group's bounding box [lower, upper].
template <typename Visit>
void forEachNearbyGroup(const PointList& points, long first, long last, std::size_t size, Visit visit)
{
  const std::vector<int> order = zOrder(points, first, last);
  for (std::size_t g = 0; g < order.size(); g += size)
  {
    const int* begin = order.data() + g;
    const int* end = order.data() + std::min(order.size(), g + size);
    Vec3 lower, upper;
    boundingBoxOf(points, begin, end, lower, upper);
    visit(begin, end, lower, upper);
  }
}
} // namespace mlsdeform
