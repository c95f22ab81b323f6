// Forward search refinement of a detected primitive (paper section 6.3, [40, 41]: Atkinson and
// Riani, "Robust Diagnostic Regression Analysis", 2000; Atkinson, Riani and Cerioli, "Exploring
// Multivariate Data with the Forward Search", 2004). RANSAC's inlier set of a primitive is a
// band of width epsilon around a fit to three samples; the forward search replaces it by the
// largest subset that a least-squares fit explains without an outlier entering:
//   1. start from the m0 candidates the current fit explains best (robust start; ties, as on
//      an exact surface, in a scrambled order so that no subset is one row of a grid);
//   2. refit to the subset, order all candidates by their distance from the new fit;
//   3. grow the subset to the next candidates in that order and repeat, until the closest
//      candidate outside the subset is farther than max(floor, Jump x the subset's RMS
//      distance): the first outlier would enter. Candidates whose normal deviates from the
//      fit's by more than the normal threshold, or that lie farther than the ceiling (the
//      RANSAC tolerance), never enter; a member the refit leaves beyond them drops out.
#pragma once

#include "Primitives/Primitives.h"

#include <algorithm>
#include <limits>

namespace mlsdeform
{
struct ForwardSearchResult
{
  Primitive shape;          // least-squares fit to the members
  std::vector<int> members; // the subset of the candidates at the stop
  double rmsDistance = 0, maxDistance = 0;
};

struct ForwardSearchSettings
{
  double floor = 0;        // distances below this never stop the search (absolute)
  double jump = 4;         // outliers are farther than this many RMS distances of the subset
  double growth = 0.3;     // the subset grows by this fraction of its size per step
  double cosAlpha = 0;     // cosine of the normal threshold
  double ceiling = std::numeric_limits<double>::infinity(); // candidates farther never enter
};

/// The distance up to which the search admits a candidate to a subset of the given RMS
/// distance: max(floor, jump x rms), never beyond the ceiling.
inline double admissionDistance(const ForwardSearchSettings& settings, double rms)
{
  return std::min(settings.ceiling, std::max(settings.floor, settings.jump * rms));
}

/// Refines start on the candidates (indices into points and their unit normals, all within the
/// RANSAC tolerance of start). Returns the members found and the fit to them.
ForwardSearchResult forwardSearch(const Primitive& start, const PointList& points, const std::vector<Vec3>& normals,
  const std::vector<int>& candidates, const ForwardSearchSettings& settings);
} // namespace mlsdeform
