#include "Common/ZOrder.h"

#include "Common/KeySort.h"

#include <algorithm>
#include <array>
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

std::uint64_t mortonCode(std::uint64_t x, std::uint64_t y, std::uint64_t z)
{
  return spread(x) | spread(y) << 1 | spread(z) << 2;
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
  std::vector<std::pair<std::uint64_t, long>> keyed(last - first);
  for (long i = first; i < last; ++i)
  {
    std::array<std::uint64_t, 3> cell;
    for (int d = 0; d < 3; ++d)
    {
      cell[d] = static_cast<std::uint64_t>(std::clamp((points[i][d] - lower[d]) / extent[d] * cells, 0.0, cells));
    }
    keyed[i - first] = { mortonCode(cell[0], cell[1], cell[2]), i };
  }
  sortByKey(keyed, 63); // ties stay in increasing index
  order.reserve(keyed.size());
  for (const auto& entry : keyed)
  {
    order.push_back(static_cast<int>(entry.second));
  }
  return order;
}
} // namespace mlsdeform
