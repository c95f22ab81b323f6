#include "ForwardSearch.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mlsdeform
{
ForwardSearchResult forwardSearch(const Primitive& start, const PointList& points, const std::vector<int>& candidates,
  const ForwardSearchSettings& settings)
{
  ForwardSearchResult result;
  result.shape = start;
  const long n = static_cast<long>(candidates.size());
  if (n == 0)
  {
    return result;
  }
  // candidates ordered by their distance from a fit: order[0..m) is the subset
  std::vector<double> distance(n);
  std::vector<long> order(n);
  auto sortBy = [&](const Primitive& shape) {
    for (long a = 0; a < n; ++a)
    {
      distance[a] = shape.distance(points[candidates[a]]);
    }
    std::iota(order.begin(), order.end(), 0L);
    std::stable_sort(order.begin(), order.end(), [&](long a, long b) { return distance[a] < distance[b]; });
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
    // the closest candidate outside the subset: an outlier when it jumps above the subset
    if (distance[order[m]] > std::max(settings.floor, settings.jump * rms))
    {
      break;
    }
    // grow to the candidates below the threshold, but by at most the growth fraction
    long next = m + std::max(1L, static_cast<long>(settings.growth * m));
    next = std::min(next, n);
    long limit = m;
    while (limit < next && distance[order[limit]] <= std::max(settings.floor, settings.jump * rms))
    {
      ++limit;
    }
    m = limit;
  }
  result.shape = shape;
  result.members = subset(m);
  std::sort(result.members.begin(), result.members.end());
  double squared = 0;
  for (int i : result.members)
  {
    const double d = shape.distance(points[i]);
    squared += d * d;
    result.maxDistance = std::max(result.maxDistance, d);
  }
  result.rmsDistance = std::sqrt(squared / static_cast<double>(result.members.size()));
  return result;
}
} // namespace mlsdeform
