// The input of the primitive detection (paper section 6.3, Fig. 7): one oriented sample per face
// of a surface mesh, its barycenter with its face normal. Vertex normals average across sharp
// feature edges and point along none of the primitives meeting there; face normals do.
#pragma once

#include "Common/CoreTypes.h"

namespace mlsdeform
{
struct FaceSamples
{
  PointList barycenters;     // area-weighted centroid of each face
  std::vector<Vec3> normals; // unit face normal (Newell's method); NaN for a degenerate face
  std::vector<double> areas; // 0 for a degenerate face
};

/// The samples of polygons given by vertex indices (any number of vertices each). A face with
/// fewer than three vertices or (numerically) zero area is degenerate: its normal is NaN, so the
/// detection skips it. Throws InvalidInputException for an index out of range or a non-finite
/// vertex used by a face.
FaceSamples faceSamples(const PointList& vertices, const std::vector<std::vector<int>>& faces);
} // namespace mlsdeform
