#include "Vocabulary/RegionRoles.h"

#include "Common/CoreTypes.h"

#include <string>

namespace mlsvtk
{
const RegionRole& regionRole(int role)
{
  if (role < 0 || role >= static_cast<int>(roles::Table.size()))
  {
    throw mlsdeform::InvalidInputException("unknown region role " + std::to_string(role) + " (0 to " +
      std::to_string(roles::Table.size() - 1) + ": " + roles::Table.front().name + " to " + roles::Table.back().name + ")");
  }
  return roles::Table[static_cast<std::size_t>(role)];
}

std::size_t fewestPoints(int role)
{
  const RegionRole& row = regionRole(role);
  return row.constraint ? mlsdeform::fewestPoints(*row.constraint) : 1;
}

int roleOfPrimitive(mlsdeform::PrimitiveType type)
{
  switch (type)
  {
    case mlsdeform::PrimitiveType::Plane:
      return roles::Planarity;
    case mlsdeform::PrimitiveType::Cylinder:
      return roles::Cylinder;
    case mlsdeform::PrimitiveType::Sphere:
    case mlsdeform::PrimitiveType::Cone:
      return roles::FeatureLine;
  }
  throw mlsdeform::InvalidInputException("unknown primitive type " + std::to_string(static_cast<int>(type)));
}
} // namespace mlsvtk
