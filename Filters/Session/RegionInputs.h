// The Regions inputs of a deformation (paper sections 3 and 6: handle and fixed regions,
// geometric constraints) as the session keeps them: this process's positions read again only
// when their VTK stamp changes, all processes' positions gathered into one canonical order
// (Common/GatheredPositions.h), and a version that changes only when those gathered values do.
#pragma once

#include "Adapters/Stamp.h"
#include "Common/Collective.h"
#include "Common/GatheredPositions.h"
#include "Solver/ShapeConstraints.h"

#include <vtkType.h>

#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkInformationVector;

namespace mlsvtk
{
struct RegionInput
{
  int role = 0; // Vocabulary/RegionRoles.h
  double weight = 1;
  bool dragging = false;   // its handle is being dragged (surface-only updates)
  mlsdeform::Plane mirror; // a Symmetric region's plane (unit normal)
  int group = 0;           // a Coplanar or Distance region's group
  mlsdeform::Vec3 axis = mlsdeform::Vec3::Zero(); // a Distance region's axis (zero: none)
  double minimumDistance = 0; // an Offset region's bound (0: its least rest distance)
  std::vector<double> localReference; // an Offset region's reference triangles here, 9 coordinates each
  vtkMTimeType referenceTime = 0;     // the modification time of the array they were read from
  std::vector<double> gatheredReference; // of all processes
  std::shared_ptr<const mlsdeform::ReferenceSurface> reference; // built from them
  Stamp stamp;
  mlsdeform::PointList localPositions;
  std::vector<int> localSets;           // a ConstraintSet per local position (CellSets), or empty
  bool localChanged = true;             // since the last gathering
  vtkDataArray* displacement = nullptr; // this update's local PrescribedDisplacement
  // the region's design variables (a Handle's; Adapters/DesignVariables.h) this update
  std::vector<std::string> variables;
  std::vector<double> values, lower, upper;
  vtkDataArray* derivatives = nullptr;  // local PrescribedDisplacementDerivatives, 3 per variable

  mlsdeform::GatheredPositions gathered; // the positions of all processes, in canonical order
  long version = -1;                     // of the gathered positions and sets (-1: none yet)
};

/// Reads this process's part of the Regions inputs (one per connection); throws
/// InvalidInputException for an input that is not a Constraint Region output, an unknown role,
/// non-finite positions or arrays of the wrong length.
void readRegions(vtkInformationVector* connections, std::vector<RegionInput>& regions);

/// Gathers the regions' positions (and an Offset region's reference surface) from all processes
/// when one process's changed; a region whose gathered values change gets the version nextVersion++. Throws InvalidInputException for a
/// region that selects no point anywhere and when no region is a Handle.
void gatherRegions(std::vector<RegionInput>& regions, long& nextVersion, const mlsdeform::Collective& group);

/// The constraint sets of a constraint region: one, or one per ConstraintSet value (CellSets). A
/// set's weight is its share of the region's positions times the region's weight, so that the sets
/// of a region together weigh as the region would as one set (every term is a mean square).
void addConstraintSets(const RegionInput& region, std::vector<mlsdeform::ShapeConstraint>& shapes);

/// The prescribed displacements of the target regions (Handle, Fixed) of all processes in their
/// gathered order, into values (one list per target region, kept between updates), viewed for
/// SpaceDeformation::solve.
std::vector<mlsdeform::PointDisplacementsView> gatherPrescribed(const std::vector<RegionInput>& regions,
  std::vector<std::vector<double>>& values, const mlsdeform::Collective& group);
} // namespace mlsvtk
