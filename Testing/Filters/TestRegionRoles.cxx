// The table of region roles (Filters/Vocabulary/RegionRoles.h) and what must follow it: the
// plugin's XML (which cannot include C++: its enumerations of roles and its panel rules by Role),
// the core's constraint types and vtkConstraintRegion's role names.
#include "../TestHarness.h"
#include "Common/CoreTypes.h"
#include "Vocabulary/RegionRoles.h"
#include "vtkConstraintRegion.h"

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <vector>

namespace
{
using Enumeration = std::map<std::string, int>; // entry text -> value

// The value of attribute `name` in the tag text, or "" without it.
std::string attribute(const std::string& tag, const std::string& name)
{
  const std::string key = " " + name + "=\"";
  const std::size_t begin = tag.find(key);
  if (begin == std::string::npos)
  {
    return "";
  }
  const std::size_t first = begin + key.size();
  return tag.substr(first, tag.find('"', first) - first);
}

// Every <EnumerationDomain> of the XML text: its entries' texts and values (a text twice counts
// as a failure).
std::vector<Enumeration> enumerations(const std::string& xml)
{
  std::vector<Enumeration> found;
  for (std::size_t at = xml.find("<EnumerationDomain"); at != std::string::npos; at = xml.find("<EnumerationDomain", at + 1))
  {
    const std::size_t end = xml.find("</EnumerationDomain>", at);
    CHECK(end != std::string::npos);
    const std::string body = xml.substr(at, end - at);
    Enumeration entries;
    for (std::size_t e = body.find("<Entry"); e != std::string::npos; e = body.find("<Entry", e + 1))
    {
      const std::string tag = body.substr(e, body.find('>', e) - e);
      const std::string text = attribute(tag, "text"), value = attribute(tag, "value");
      CHECK(!text.empty() && !value.empty());
      CHECK(entries.count(text) == 0);
      entries[text] = std::stoi(value);
    }
    found.push_back(entries);
  }
  return found;
}

// Whether an enumeration names roles: an entry named like the first target or constraint role.
bool namesRoles(const Enumeration& entries)
{
  return entries.count(mlsvtk::roles::Table[mlsvtk::roles::Handle].name) ||
    entries.count(mlsvtk::roles::Table[mlsvtk::roles::Planarity].name);
}

// The table as an enumeration: name -> value.
Enumeration tableEnumeration()
{
  Enumeration table;
  for (std::size_t r = 0; r < mlsvtk::roles::Table.size(); ++r)
  {
    table[mlsvtk::roles::Table[r].name] = static_cast<int>(r);
  }
  return table;
}

// Prints the differences of an XML enumeration from the table; true when there is none.
bool sameAsTable(const Enumeration& xml)
{
  const Enumeration table = tableEnumeration();
  for (const auto& [name, value] : table)
  {
    if (!xml.count(name) || xml.at(name) != value)
    {
      std::printf("role %s (value %d): %s in the XML\n", name.c_str(), value,
        xml.count(name) ? ("value " + std::to_string(xml.at(name))).c_str() : "missing");
    }
  }
  for (const auto& [name, value] : xml)
  {
    if (!table.count(name))
    {
      std::printf("XML entry %s (value %d) is no role of the table\n", name.c_str(), value);
    }
  }
  return xml == table;
}
}

// Every XML enumeration of roles has the table's names and values, no more and no fewer.
TEST(MatchesXML)
{
  std::ifstream file(MLSDEFORM_PLUGIN_XML);
  CHECK(file.good());
  std::stringstream xml;
  xml << file.rdbuf();
  int roleEnumerations = 0;
  for (const Enumeration& entries : enumerations(xml.str()))
  {
    if (namesRoles(entries))
    {
      ++roleEnumerations;
      CHECK(sameAsTable(entries));
    }
  }
  CHECK(roleEnumerations >= 1);
  // the comparison fails on a wrong value, a missing and an extra role
  std::printf("expected differences:\n");
  Enumeration wrong = tableEnumeration(), missing = wrong, extra = wrong;
  wrong["Slip"] = 9;
  missing.erase("Rigid");
  extra["Bend"] = 9;
  CHECK(!sameAsTable(wrong) && !sameAsTable(missing) && !sameAsTable(extra));
}

// The panel's visibility rules by Role hold the table's values: CellSets for the roles whose
// regions it splits per cell (the constraints other than Slip, and FromPrimitive, which stands for
// one of them), the Handle Motion group for Handle. A new rule by Role must be added here.
TEST(XMLDecoratorsByRole)
{
  std::ifstream file(MLSDEFORM_PLUGIN_XML);
  std::stringstream stream;
  stream << file.rdbuf();
  const std::string xml = stream.str();
  std::map<std::string, std::set<int>> shownFor; // the element a decorator is in -> its Role values
  const std::string decorator = "<PropertyWidgetDecorator";
  for (std::size_t at = xml.find(decorator); at != std::string::npos; at = xml.find(decorator, at + 1))
  {
    const std::string tag = xml.substr(at, xml.find('>', at) - at);
    if (attribute(tag, "property") != "Role")
    {
      continue;
    }
    // the enclosing property (an ...Property tag, not a group's <Property> member) or group
    std::size_t property = xml.rfind("Property name=\"", at);
    while (property != std::string::npos && property > 0 && xml[property - 1] == '<')
    {
      property = xml.rfind("Property name=\"", property - 1);
    }
    const std::size_t group = xml.rfind("<PropertyGroup label=\"", at);
    const std::size_t owner = property == std::string::npos || (group != std::string::npos && group > property) ? group : property;
    CHECK(owner != std::string::npos);
    const std::string ownerTag = xml.substr(owner, xml.find('>', owner) - owner);
    const std::string name = ownerTag.find("<PropertyGroup") == 0 ? attribute(ownerTag, "label") : attribute(" " + ownerTag, "name");
    std::stringstream values(attribute(tag, "values") + " " + attribute(tag, "value"));
    for (int v; values >> v;)
    {
      shownFor[name].insert(v);
    }
  }
  std::set<int> cellSets{ mlsvtk::roles::FromPrimitive };
  for (int role = 0; role < static_cast<int>(mlsvtk::roles::Table.size()); ++role)
  {
    if (mlsvtk::isConstraint(role) && !mlsdeform::measuresPlaces(*mlsvtk::regionRole(role).constraint))
    {
      cellSets.insert(role);
    }
  }
  const std::map<std::string, std::set<int>> expected{ { "CellSets", cellSets }, { "Handle Motion", { mlsvtk::roles::Handle } },
    { "DesignVariables", { mlsvtk::roles::Handle } }, { "SymmetryOrigin", { mlsvtk::roles::Symmetric } },
    { "SymmetryNormal", { mlsvtk::roles::Symmetric } }, { "ConstraintGroup", { mlsvtk::roles::Coplanar, mlsvtk::roles::Distance } },
    { "DistanceAxis", { mlsvtk::roles::Distance } }, { "MinimumDistance", { mlsvtk::roles::Offset } }, { "Surface", { mlsvtk::roles::Offset } },
    { "UseCentroid", { mlsvtk::roles::Handle } }, { "Center", { mlsvtk::roles::Handle } } };
  for (const auto& [name, roles] : shownFor)
  {
    std::printf("shown by Role: %s\n", name.c_str());
  }
  CHECK(shownFor == expected);
}

// An unknown value is an error, not a default row.
TEST(UnknownRoleThrows)
{
  CHECK_THROWS(mlsvtk::regionRole(-1), mlsdeform::InvalidInputException);
  const int beyond = static_cast<int>(mlsvtk::roles::Table.size());
  CHECK_THROWS(mlsvtk::regionRole(beyond), mlsdeform::InvalidInputException);
  CHECK_THROWS(mlsvtk::isConstraint(beyond), mlsdeform::InvalidInputException);
  CHECK_THROWS(mlsvtk::fewestPoints(-1), mlsdeform::InvalidInputException);
}

// Geometric constraints are the rows with a core constraint; the targets and FromPrimitive
// (which stands for its primitive's constraint) are none. The fewest points are the core's.
TEST(ConstraintsAndFewestPoints)
{
  using namespace mlsvtk::roles;
  using mlsdeform::ConstraintType;
  const std::map<int, ConstraintType> constraints{ { Planarity, ConstraintType::Planarity },
    { Circularity, ConstraintType::Circularity }, { Cylinder, ConstraintType::Cylinder },
    { FeatureLine, ConstraintType::FeatureLine }, { Rigid, ConstraintType::Rigid }, { Slip, ConstraintType::Slip },
    { Symmetric, ConstraintType::Symmetric }, { Coplanar, ConstraintType::Coplanar },
    { Distance, ConstraintType::Distance }, { Offset, ConstraintType::Offset } };
  for (int role = 0; role < static_cast<int>(Table.size()); ++role)
  {
    const bool constraint = constraints.count(role) > 0;
    CHECK(mlsvtk::isConstraint(role) == constraint);
    CHECK(mlsvtk::regionRole(role).constraint.has_value() == constraint);
    if (constraint)
    {
      CHECK(*mlsvtk::regionRole(role).constraint == constraints.at(role));
      CHECK(mlsvtk::fewestPoints(role) == mlsdeform::fewestPoints(constraints.at(role)));
      CHECK(std::string(mlsdeform::constraintName(constraints.at(role))) == Table[role].name);
    }
  }
  CHECK(mlsvtk::fewestPoints(Handle) == 1);
  CHECK(mlsvtk::fewestPoints(Fixed) == 1);
}

// Section 6.3: a plane keeps its planarity, a cylinder stays a cylinder, a sphere and a cone
// keep their shape by a similarity (FeatureLine).
TEST(RoleOfPrimitive)
{
  using mlsdeform::PrimitiveType;
  CHECK(mlsvtk::roleOfPrimitive(PrimitiveType::Plane) == mlsvtk::roles::Planarity);
  CHECK(mlsvtk::roleOfPrimitive(PrimitiveType::Cylinder) == mlsvtk::roles::Cylinder);
  CHECK(mlsvtk::roleOfPrimitive(PrimitiveType::Sphere) == mlsvtk::roles::FeatureLine);
  CHECK(mlsvtk::roleOfPrimitive(PrimitiveType::Cone) == mlsvtk::roles::FeatureLine);
}

// vtkConstraintRegion names every role as the table does, and an unknown value "Unknown".
TEST(ConstraintRegionNames)
{
  for (int role = 0; role < static_cast<int>(mlsvtk::roles::Table.size()); ++role)
  {
    CHECK(std::string(vtkConstraintRegion::GetRoleName(role)) == mlsvtk::roles::Table[role].name);
  }
  CHECK(std::string(vtkConstraintRegion::GetRoleName(-1)) == "Unknown");
  CHECK(std::string(vtkConstraintRegion::GetRoleName(vtkConstraintRegion::Offset + 1)) == "Unknown");
}

TEST_MAIN
