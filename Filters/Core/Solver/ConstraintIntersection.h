// Exact constraints: positions that satisfy every constrained point set at once and keep the
// targets among them, found by alternating projections (von Neumann; Bauschke and Borwein 1996)
// from the deformation's positions. Each step projects every set onto its constraint (the
// Shape-Up projections of section 6.2), gives a position shared by several sets the mean of
// their projections, and puts the target positions back. A step that moves no position by more
// than the tolerance is a point of every constraint (within it) that meets every target: the
// exact projection step. When the sets and targets contradict each other (a planar region that a
// handle must bend), the steps stall at a gap: the sets with the largest gaps are the conflicting
// ones.
#pragma once

#include "Common/CoreTypes.h"

#include <functional>

namespace mlsdeform
{
struct IntersectionResult
{
  PointList positions;     // per site
  std::vector<double> gap; // per set: the largest distance of its points from their projection at the last step
  int iterations = 0;
  bool converged = false;
};

/// sets: per constrained set, the site of each of its points; project: every set's projection of
/// its points' positions (sets in order); start: per site; pinned: per site, whether it is a target
/// (kept at its start). Stops when the largest gap is at most tolerance, or when it stalls: the
/// steps converge linearly, and a gap that shrank by less than 1% over the last 100 steps would
/// need tens of thousands more (a contradiction: the gap tends to a positive limit), or after
/// maxIterations.
IntersectionResult projectOntoIntersection(const std::vector<std::vector<long>>& sets,
  const std::function<std::vector<PointList>(const std::vector<PointList>&)>& project, const PointList& start,
  const std::vector<char>& pinned, double tolerance, int maxIterations);
} // namespace mlsdeform
