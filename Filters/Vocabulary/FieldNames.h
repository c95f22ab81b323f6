// The names of the arrays that pass between the filters (and reach scripts and the GUI): one
// definition each, so that a producer and its consumers cannot disagree.
#pragma once

namespace mlsvtk::fields
{
// Constraint Region output -> MLS Deform / Shell Deform
constexpr const char* Role = "Role";                       // field data, int: the role's value (RegionRoles.h)
constexpr const char* RoleName = "RoleName";               // field data, string
constexpr const char* Weight = "Weight";                   // field data, double
constexpr const char* PrescribedDisplacement = "PrescribedDisplacement"; // point data, 3 components
constexpr const char* ConstraintSet = "ConstraintSet";     // point data: the constraint set of a position (CellSets; a Slip region's blocks)
constexpr const char* SymmetryPlane = "SymmetryPlane";     // field data, 6 components: a Symmetric region's origin and normal
constexpr const char* ConstraintGroup = "ConstraintGroup"; // field data, int: a Coplanar or Distance region's group
constexpr const char* DistanceAxis = "DistanceAxis";       // field data, 3 components: a Distance region's axis (zero: none)
constexpr const char* MinimumDistance = "MinimumDistance"; // field data, double: an Offset region's bound (0: its rest distance)
constexpr const char* ReferenceTriangles = "ReferenceTriangles"; // field data, 9 components: an Offset region's reference surface
constexpr const char* Dragging = "Dragging";               // field data, int: 1 while the region's handle is dragged (surface-only updates)
// design variables (Adapters/DesignVariables.h): on a Handle region's output and, for all
// regions together, on MLS Deform's output
constexpr const char* DesignVariableNames = "DesignVariableNames";   // field data, string per variable
constexpr const char* DesignVariableValues = "DesignVariableValues"; // field data, double per variable
constexpr const char* DesignVariableBounds = "DesignVariableBounds"; // field data, (lower, upper) per variable
constexpr const char* PrescribedDerivatives = "PrescribedDisplacementDerivatives"; // point data: d(dbar)/dp, 3 per variable
constexpr const char* ControlDirection = "ControlDirection"; // point data of a region with control points: each held point's direction a
// MLS Deform / Shell Deform output
constexpr const char* Displacement = "Displacement";       // point data, 3 components
constexpr const char* TargetConflicts = "TargetConflicts";         // field data, string: regions whose targets disagree
constexpr const char* ConstraintConflicts = "ConstraintConflicts"; // field data, string: constraint regions that cannot hold exactly
constexpr const char* SensitivityPrefix = "dX/d";          // point data "dX/d<variable>", 3 components (ComputeSensitivities)
constexpr const char* ObjectiveSensitivity = "ObjectiveSensitivity"; // field data: dJ/dp per variable (ObjectiveGradientArray)
constexpr const char* SensitivityMethod = "SensitivityMethod";       // field data, string: how the derivatives were computed
/// Field-data string on an output whose filter failed: the message (the output window has it too).
constexpr const char* Error = "DeformationError";
// MLS Sampler output -> MLS Deform
constexpr const char* SupportRadius = "SupportRadius";     // point data of the samples
constexpr const char* OnSurface = "OnSurface";             // point data of the samples
constexpr const char* Volume = "Volume";                   // point data of the integration points
// Primitive Detector output -> Constraint Region
constexpr const char* PrimitiveId = "PrimitiveId";         // cell data
constexpr const char* PrimitiveType = "PrimitiveType";     // cell data
constexpr const char* PrimitiveIds = "PrimitiveIds";       // point data, padded with -1
constexpr const char* PrimitiveCount = "PrimitiveCount";   // point data
constexpr const char* PrimitiveTypes = "PrimitiveTypes";   // field data: the type of each primitive id
} // namespace mlsvtk::fields
