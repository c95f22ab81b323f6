// Local shape variables (pyGeo's DVGeometry.addLocalDV; the paper's direct manipulation of
// surface points, section 4): a Handle region's control points, each held at
//   x' = x + motion(x) + p_v a
// where p_v is the value of its Local design variable v and a the control point's direction
// times its coefficient, or, when it is given as zero, the unit normal of the region's surface
// there pointing out of the mesh (the orientation of a mesh's boundary faces, OpenFOAM's: on a
// CFD case's wall into the body, on a solid's surface out of it). Every other point of the region
// is free: the surface between control points bends as the energy minimization (paper eq. 14)
// lets it. dx'/dp_v = a at the control points of v, 0 elsewhere.
//
// A control point given with a line axis holds every point of the region on the line through it
// along that axis (the depth of a one-cell-thick 2D case, the thickness of an extruded plate),
// all by the same a, whose component along the axis is removed for a normal: an extruded shape
// stays extruded. A control point snaps to the region's nearest point.
#pragma once

#include "Adapters/DesignVariables.h"
#include "Common/Collective.h"
#include "Common/CoreTypes.h"

#include <string>
#include <vector>

class vtkPointSet;

namespace mlsvtk
{
struct ControlPoint
{
  std::string variable;                                // a Local design variable of the region
  mlsdeform::Vec3 position = mlsdeform::Vec3::Zero();  // snapped to the region's nearest point
  mlsdeform::Vec3 direction = mlsdeform::Vec3::Zero(); // a; zero: the outward unit normal there
  mlsdeform::Vec3 lineAxis = mlsdeform::Vec3::Zero();  // zero: the point alone
  bool operator==(const ControlPoint& o) const
  {
    return variable == o.variable && position == o.position && direction == o.direction && lineAxis == o.lineAxis;
  }
};

/// The positions control points hold, resolved against a region's selection.
struct HeldPositions
{
  mlsdeform::PointList positions;          // this process's held positions, in the order of its selection
  std::vector<int> control;                // per held position: its control point
  std::vector<mlsdeform::Vec3> snapped;    // per control point: the region's point it snapped to
  std::vector<mlsdeform::Vec3> directions; // per control point: a
};

/// Throws mlsdeform::InvalidInputException unless every control point names a Local variable of
/// variables and has finite coordinates, and every Local variable has a control point.
void checkControlPoints(const std::vector<ControlPoint>& controls, const std::vector<DesignVariable>& variables);

/// The positions of the selection (this process's, of the point sets sets) that the control
/// points hold, the same on any split over processes. Throws mlsdeform::InvalidInputException
/// when there are more control points than the region has points (or lines), two control points
/// share a position, or a normal is asked where the region has no surface (a point cloud).
HeldPositions holdControlPoints(const std::vector<ControlPoint>& controls, const mlsdeform::PointList& selected,
  const std::vector<vtkPointSet*>& sets, const mlsdeform::Collective& group);

/// count positions spread evenly over the selection (all processes' positions): farthest-point
/// sampling from the least position (coordinates compared in turn), distances measured across
/// lineAxis when it is not zero (one position a line). Deterministic: the same on any split.
/// Throws mlsdeform::InvalidInputException when the selection has fewer positions (lines).
mlsdeform::PointList spreadControlPoints(const mlsdeform::PointList& selected, int count, const mlsdeform::Vec3& lineAxis,
  const mlsdeform::Collective& group);
} // namespace mlsvtk
