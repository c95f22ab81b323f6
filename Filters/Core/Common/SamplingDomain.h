// A simplicial domain: points, surface triangles, volume tetrahedra. What the sampling samples
// and what the mesh-based operators (ShellOperators.h) integrate over.
#pragma once

#include "Common/CoreTypes.h"

#include <array>
#include <vector>

namespace mlsdeform
{
/// What is sampled: all points, the surface as triangles and the volume as tetrahedra (indices
/// into points). Without tetrahedra the embedding space is the bounding box of the points, padded
/// by SamplingParameters::boundsPadding; without triangles the points themselves are the surface.
struct SamplingDomain
{
  PointList points;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 4>> tetrahedra;
};
} // namespace mlsdeform
