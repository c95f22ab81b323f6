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
  // the candidates' distances from a fit; a candidate whose normal the fit does not match or
  // that lies beyond the ceiling cannot enter (infinite distance)
  std::vector<double> distance(n);
  auto measure = [&](const Primitive& shape) {
#pragma omp parallel for schedule(static) if (n >= ParallelSamples)
    for (long a = 0; a < n; ++a)
    {
      const int i = candidates[a];
      Vec3 normal;
      const double d = shape.distance(points[i], normal);
      distance[a] = std::abs(normals[i].dot(normal)) >= settings.cosAlpha && d <= settings.ceiling
        ? d
        : std::numeric_limits<double>::infinity();
    }
  };
  // candidates by distance; ties (an exact surface) in a scrambled but fixed order, so that a
  // growing subset spreads over the surface instead of filling it row by row (a row would make
  // a degenerate fit). A total order: the m closest are one set whatever the arrangement.
  auto scrambled = [](long a) { return (static_cast<std::uint64_t>(a) * 0x9E3779B97F4A7C15ull) >> 16; };
  auto closer = [&](long a, long b) {
    return distance[a] < distance[b] ||
      (distance[a] == distance[b] && (scrambled(a) < scrambled(b) || (scrambled(a) == scrambled(b) && a < b)));
  };
  // order[0..m) is the subset: the m closest candidates, selected (O(n)) rather than sorted
  // (O(n log n)): the fit does not depend on their order beyond round-off, and the selection's
  // arrangement is fixed for its input
  std::vector<long> order(n);
  std::iota(order.begin(), order.end(), 0L);
  auto select = [&](long m) {
    if (m < n)
    {
      std::nth_element(order.begin(), order.begin() + m, order.end(), closer);
    }
  };
  auto subset = [&](long m) {
    std::vector<int> s(m);
    for (long a = 0; a < m; ++a)
    {
      s[a] = candidates[order[a]];
    }
    return s;
  };
  measure(start);
  // start: the m0 candidates the current fit explains best
  long m = std::min(n, std::max(10L, n / 10));
  select(m);
  Primitive shape = start;
  while (true)
  {
    shape = fitLeastSquares(shape, points, subset(m));
    measure(shape);
    select(m); // order[m] is now the closest candidate outside the subset
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
    const double admitted = admissionDistance(settings, rms);
    if (!std::isfinite(rms) || distance[order[m]] > admitted)
    {
      break;
    }
    // grow to the candidates below the threshold, but by at most the growth fraction
    const long next = std::min(n, m + std::max(1L, static_cast<long>(settings.growth * m)));
    const long below = std::count_if(distance.begin(), distance.end(), [&](double d) { return d <= admitted; });
    m = std::min(next, below);
    select(m);
  }
  std::vector<int> members;
  for (long a = 0; a < m; ++a)
  {
    if (std::isfinite(distance[order[a]]))
    {
      members.push_back(candidates[order[a]]); // members the last fit no longer matches leave
    }
  }
  result.shape = shape;
  result.members = std::move(members);
  std::sort(result.members.begin(), result.members.end());
  const DistanceStatistics statistics = distanceStatistics(shape, points, result.members);
  result.rmsDistance = statistics.rms;
  result.maxDistance = statistics.max;
  return result;
}
} // namespace mlsdeform
