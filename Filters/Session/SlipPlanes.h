// The Slip regions' planes (ground, symmetry, inlet and outlet planes of a CFD domain): every
// point of the input that lies on a plane within its region's bounds slides within the plane (a
// space deformation knows positions only, so a patch and the volume mesh that share a point treat
// it alike). A region with constraint sets (the blocks of a region selected by name) has a plane
// per set.
#pragma once

#include "Common/BoundingBox.h"
#include "Solver/ConstraintProjections.h"
#include "Session/RegionInputs.h"

#include <vector>

namespace mlsvtk
{
struct SlipPlane
{
  mlsdeform::Plane plane;
  mlsdeform::BoundingBox bounds; // the region's box, enlarged by the plane's tolerance
  double tolerance = 0;

  bool holds(const mlsdeform::Vec3& x) const
  {
    return (x.array() >= bounds.lower.array()).all() && (x.array() <= bounds.upper.array()).all() &&
      std::abs(plane.normal.dot(x - plane.point)) <= tolerance;
  }
};

/// The Slip regions' planes; throws InvalidInputException for a region that is not planar (its
/// points farther than 1e-6 of its diagonal from their plane: round-off of float coordinates is 1e-7).
std::vector<SlipPlane> slipPlanes(const std::vector<RegionInput>& regions);

/// The displacement d of the points [offset, offset + n) on a slip plane loses its normal
/// component: the constraint iteration leaves them within its tolerance of the plane, this puts
/// them on it (as OpenFOAM's slip does). transposed: the transposed map (the planes in reverse
/// order), for the reverse mode of design sensitivities.
void slideOnPlanes(const std::vector<SlipPlane>& planes, const mlsdeform::PointList& points, long offset, long n, double* d,
  bool transposed = false);
/// The same for the listed points (d: 3 values per entry of rows).
void slideRowsOnPlanes(const std::vector<SlipPlane>& planes, const mlsdeform::PointList& points, const std::vector<long>& rows,
  double* d, bool transposed);
} // namespace mlsvtk
