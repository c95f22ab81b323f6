#include "Solver/ConstraintIntersection.h"

#include <algorithm>
#include <limits>

namespace mlsdeform
{
IntersectionResult projectOntoIntersection(const std::vector<std::vector<long>>& sets,
  const std::function<std::vector<PointList>(const std::vector<PointList>&)>& project, const PointList& start,
  const std::vector<char>& pinned, double tolerance, int maxIterations)
{
  IntersectionResult result;
  result.positions = start;
  PointList& z = result.positions;
  std::vector<double> count(z.size(), 0.0); // sets per site
  for (const std::vector<long>& set : sets)
  {
    for (long s : set)
    {
      count[s] += 1;
    }
  }
  constexpr int Window = 100;         // steps between two looks at the gap's progress
  constexpr double LeastProgress = 0.99; // the gap must shrink below this fraction of its value a window ago
  double windowGap = std::numeric_limits<double>::infinity();
  std::vector<PointList> y(sets.size());
  PointList sum(z.size());
  for (int i = 0; i < maxIterations; ++i)
  {
    for (std::size_t t = 0; t < sets.size(); ++t)
    {
      y[t].resize(sets[t].size());
      for (std::size_t a = 0; a < sets[t].size(); ++a)
      {
        y[t][a] = z[sets[t][a]];
      }
    }
    const std::vector<PointList> p = project(y);
    result.gap.assign(sets.size(), 0.0);
    std::fill(sum.begin(), sum.end(), Vec3::Zero());
    for (std::size_t t = 0; t < sets.size(); ++t)
    {
      for (std::size_t a = 0; a < sets[t].size(); ++a)
      {
        result.gap[t] = std::max(result.gap[t], (p[t][a] - y[t][a]).norm());
        sum[sets[t][a]] += p[t][a];
      }
    }
    result.iterations = i + 1;
    const double gap = *std::max_element(result.gap.begin(), result.gap.end());
    if (gap <= tolerance)
    {
      result.converged = true;
      break;
    }
    if (i % Window == 0)
    {
      if (gap > LeastProgress * windowGap)
      {
        break; // stalled
      }
      windowGap = gap;
    }
    for (std::size_t s = 0; s < z.size(); ++s)
    {
      if (!pinned[s] && count[s] > 0)
      {
        z[s] = sum[s] / count[s];
      }
    }
  }
  return result;
}
} // namespace mlsdeform
