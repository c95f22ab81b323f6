// A 2D case extruded along one axis (an OpenFOAM case whose front and back planes are an `empty`
// patch): the deformation becomes d(x) = S_a Phi(P_a x) w, with P_a setting x's coordinate along
// the axis to the input's middle and S_a removing d's component along the axis, so that d does not
// vary along the axis and never leaves the plane normal to it: the front and back copies of a point
// move alike, the planes stay planes and the mesh stays 2D (checkMesh's "edges not aligned with or
// perpendicular to non-empty directions"). Slip regions on the front and back planes are then
// implied exactly and are not iterated on; geometric constraints of other roles are not supported.
#pragma once

#include "Common/CoreTypes.h"
#include "Session/SlipPlanes.h"

namespace mlsvtk
{
struct Extrusion
{
  int axis = -1;      // 0, 1, 2: x, y, z; -1: none (a 3D deformation)
  double middle = 0;  // the input's middle along the axis (the mid-plane of all processes' points)

  bool active() const { return axis >= 0; }

  /// The positions Phi is evaluated at: P_a x (x itself, without a copy, when none; else a copy
  /// into storage).
  const mlsdeform::PointList& evaluated(const mlsdeform::PointList& x, mlsdeform::PointList& storage) const;

  /// S_a as a slip plane that holds at every point.
  SlipPlane slide() const;

  /// Whether positions lie in one plane normal to the axis (within tolerance): a front or back plane.
  bool normalPlane(const mlsdeform::PointList& positions, double tolerance) const;
};
} // namespace mlsvtk
