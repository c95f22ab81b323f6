#include "Primitives/ForwardSearch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace mlsdeform
{
ForwardSearchResult forwardSearch(const Primitive& start, const PointList& points, const std::vector<Vec3>& normals,
  const std::vector<int>& candidates, const ForwardSearchSettings& settings)
{
  ForwardSearchResult result;
  result.shape = start;
  const long n = static_cast<long>(candidates.size());
  if (n == 0)
  {
    return result;
  }
  // candidates ordered by their distance from a fit: order[0..m) is the subset; a candidate whose
  // normal the fit does not match or that lies beyond the ceiling cannot enter
  std::vector<double> distance(n);
  std::vector<long> order(n);
  auto sortBy = [&](const Primitive& shape) {
    for (long a = 0; a < n; ++a)
    {
      const int i = candidates[a];
      const double d = shape.distance(points[i]);
      distance[a] = std::abs(normals[i].dot(shape.normalAt(points[i]))) >= settings.cosAlpha && d <= settings.ceiling
        ? d
        : std::numeric_limits<double>::infinity();
    }
    // ties (an exact surface) in a scrambled but fixed order, so that a growing subset spreads
    // over the surface instead of filling it row by row (a row would make a degenerate fit)
    std::iota(order.begin(), order.end(), 0L);
    auto scrambled = [](long a) { return (static_cast<std::uint64_t>(a) * 0x9E3779B97F4A7C15ull) >> 16; };
    std::sort(order.begin(), order.end(), [&](long a, long b) {
      return distance[a] < distance[b] || (distance[a] == distance[b] && scrambled(a) < scrambled(b));
    });
  };
  auto subset = [&](long m) {
    std::vector<int> s(m);
    for (long a = 0; a < m; ++a)
    {
      s[a] = candidates[order[a]];
    }
    return s;
  };
  sortBy(start);
  // start: the m0 candidates the current fit explains best
  long m = std::min(n, std::max(10L, n / 10));
  Primitive shape = start;
  while (true)
  {
    shape = fitLeastSquares(shape, points, subset(m));
    sortBy(shape);
    if (m == n)
    {
      break;
    }
    double squared = 0;
    for (long a = 0; a < m; ++a)
    {
      squared += distance[order[a]] * distance[order[a]];
    }
    const double rms = std::sqrt(squared / m);
    // the closest candidate outside the subset: an outlier when it jumps above the subset (or
    // when the subset itself no longer fits: a member with a mismatched normal)
    if (!std::isfinite(rms) || distance[order[m]] > admissionDistance(settings, rms))
    {
      break;
    }
    // grow to the candidates below the threshold, but by at most the growth fraction
    long next = m + std::max(1L, static_cast<long>(settings.growth * m));
    next = std::min(next, n);
    long limit = m;
    while (limit < next && distance[order[limit]] <= admissionDistance(settings, rms))
    {
      ++limit;
    }
    m = limit;
  }
  while (m > 0 && !std::isfinite(distance[order[m - 1]]))
  {
    --m; // members the last fit no longer matches leave (the distances are sorted)
  }
  result.shape = shape;
  result.members = subset(m);
  std::sort(result.members.begin(), result.members.end());
  const DistanceStatistics statistics = distanceStatistics(shape, points, result.members);
  result.rmsDistance = statistics.rms;
  result.maxDistance = statistics.max;
  return result;
}
} // namespace mlsdeform
