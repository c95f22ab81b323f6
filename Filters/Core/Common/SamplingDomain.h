// A simplicial domain: points, surface triangles, volume tetrahedra. What the sampling samples
// and what the mesh-based operators (ShellOperators.h) integrate over.
#pragma once

#include "Common/CoreTypes.h"
#include "Common/UninitializedVector.h"

#include <array>
#include <vector>

namespace mlsdeform
{
/// Simplices as N indices into points each (triangles N = 3, tetrahedra N = 4), filled in
/// parallel: 6M tetrahedra on a 1M-cell mesh, 96 MB that one thread zeroed and copied took a
/// quarter of a second.
template <std::size_t N>
using Simplices = UninitializedVector<std::array<int, N>>;

/// What is sampled: all points, the surface as triangles and the volume as tetrahedra (indices
/// into points). Without tetrahedra the embedding space is the bounding box of the points, padded
/// by SamplingParameters::boundsPadding; without triangles the points themselves are the surface.
struct SamplingDomain
{
  PointList points;
  Simplices<3> triangles;
  Simplices<4> tetrahedra;
};
} // namespace mlsdeform
