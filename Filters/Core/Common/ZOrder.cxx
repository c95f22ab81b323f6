#include "Common/ZOrder.h"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace mlsdeform
{
namespace
{
// The 21 low bits of v spread to every third bit.
std::uint64_t spread(std::uint64_t v)
{
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffff;
  v = (v | v << 16) & 0x1f0000ff0000ff;
  v = (v | v << 8) & 0x100f00f00f00f00f;
  v = (v | v << 4) & 0x10c30c30c30c30c3;
  v = (v | v << 2) & 0x1249249249249249;
  return v;
}
}

std::vector<int> zOrder(const PointList& points, long first, long last)
{
  std::vector<int> order;
  if (last <= first)
  {
    return order;
  }
  Vec3 lower = points[first], upper = points[first];
  for (long i = first + 1; i < last; ++i)
  {
    lower = lower.cwiseMin(points[i]);
    upper = upper.cwiseMax(points[i]);
  }
  const double cells = 0x1fffff;
  const Vec3 extent = (upper - lower).cwiseMax(1e-300);
  std::vector<std::pair<std::uint64_t, int>> keyed(last - first);
  for (long i = first; i < last; ++i)
  {
    std::uint64_t key = 0;
    for (int d = 0; d < 3; ++d)
    {
      const double cell = std::clamp((points[i][d] - lower[d]) / extent[d] * cells, 0.0, cells);
      key |= spread(static_cast<std::uint64_t>(cell)) << d;
    }
    keyed[i - first] = { key, static_cast<int>(i) };
  }
  std::sort(keyed.begin(), keyed.end());
  order.reserve(keyed.size());
  for (const auto& entry : keyed)
  {
    order.push_back(entry.second);
  }
  return order;
}
} // namespace mlsdeform
