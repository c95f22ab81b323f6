// The roles a Constraint Region gives its positions (paper sections 3 and 6), one row per role:
// its value (saved in state files and passed in the field data "Role"), its name, its colour in
// the GUI, whether it is a geometric constraint (kept by projections, section 6) or a target
// (eq. 14), the core's constraint type and the fewest points it needs. vtkConstraintRegion's enum,
// the plugin's XML enumeration (checked by Filters.RegionRoles.MatchesXML) and the GUI's colours
// follow this table. A new constraint type: one row here, one in the core's ConstraintTypes and
// its projection (ARCHITECTURE.md).
#pragma once

#include "MLSDeformFiltersModule.h"
#include "Primitives/Primitives.h"
#include "Solver/ShapeConstraints.h"

#include <array>
#include <optional>

namespace mlsvtk
{
struct RegionRole
{
  const char* name;
  std::array<double, 3> colour; // RGB of the region's points in the GUI
  /// The core's constraint of a geometric-constraint role; none for a target (Handle, Fixed) and
  /// for FromPrimitive (which stands for the role of its primitive's type).
  std::optional<mlsdeform::ConstraintType> constraint;
};

namespace roles
{
constexpr std::array<double, 3> TargetRed{ 0.9, 0.1, 0.1 }, TargetBlue{ 0.15, 0.35, 1.0 }, Green{ 0.1, 0.75, 0.2 },
  Orange{ 1.0, 0.6, 0.0 };
using mlsdeform::ConstraintType;
/// Indexed by the role's value. Slip comes after FromPrimitive so that saved states keep their values.
inline constexpr std::array<RegionRole, 13> Table{ {
  { "Handle", TargetRed, std::nullopt },
  { "Fixed", TargetBlue, std::nullopt },
  { "Planarity", Green, ConstraintType::Planarity },
  { "Circularity", Green, ConstraintType::Circularity },
  { "Cylinder", Green, ConstraintType::Cylinder },
  { "FeatureLine", Green, ConstraintType::FeatureLine },
  { "Rigid", Green, ConstraintType::Rigid },
  { "FromPrimitive", Green, std::nullopt },
  { "Slip", Orange, ConstraintType::Slip },
  { "Symmetric", Green, ConstraintType::Symmetric },
  { "Coplanar", Green, ConstraintType::Coplanar },
  { "Distance", Green, ConstraintType::Distance },
  { "Offset", Green, ConstraintType::Offset },
} };
/// The values by name (vtkConstraintRegion's enum static_asserts that it has the same).
constexpr int Handle = 0, Fixed = 1, Planarity = 2, Circularity = 3, Cylinder = 4, FeatureLine = 5, Rigid = 6, FromPrimitive = 7,
              Slip = 8, Symmetric = 9, Coplanar = 10, Distance = 11, Offset = 12;
static_assert(Table.size() == Offset + 1, "one row per role");
}

/// The row of a role value; throws mlsdeform::InvalidInputException for an unknown value.
MLSDEFORMFILTERS_EXPORT const RegionRole& regionRole(int role);

/// Whether the role is a geometric constraint (its points kept by a projection, section 6).
inline bool isConstraint(int role)
{
  return regionRole(role).constraint.has_value();
}

/// The fewest points a region of the role needs: the constraint's, or one for a target.
MLSDEFORMFILTERS_EXPORT std::size_t fewestPoints(int role);

/// The role that keeps a detected primitive of the type (section 6.3): Planarity for a plane,
/// Cylinder for a cylinder, FeatureLine (a similarity keeps a sphere a sphere and a cone's angle)
/// for a sphere or a cone.
MLSDEFORMFILTERS_EXPORT int roleOfPrimitive(mlsdeform::PrimitiveType type);
} // namespace mlsvtk
