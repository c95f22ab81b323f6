#include "Session/RegionInputs.h"

#include "Adapters/PointSets.h"
#include "Common/BoundingBox.h"
#include "Vocabulary/FieldNames.h"
#include "Vocabulary/RegionRoles.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

using namespace mlsdeform;

namespace mlsvtk
{
namespace
{
// The design variables of a region's output (vtkConstraintRegion::AddDesignVariable), if any.
void readDesignVariables(vtkPolyData* data, const std::string& which, RegionInput& region)
{
  region.variables.clear();
  region.values.clear();
  region.lower.clear();
  region.upper.clear();
  region.derivatives = nullptr;
  auto* names = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(fields::DesignVariableNames));
  if (!names || names->GetNumberOfValues() == 0)
  {
    return;
  }
  const vtkIdType m = names->GetNumberOfValues();
  vtkDataArray* values = data->GetFieldData()->GetArray(fields::DesignVariableValues);
  vtkDataArray* bounds = data->GetFieldData()->GetArray(fields::DesignVariableBounds);
  vtkDataArray* derivatives = data->GetPointData()->GetArray(fields::PrescribedDerivatives);
  if (!values || values->GetNumberOfTuples() != m || !bounds || bounds->GetNumberOfTuples() != m || bounds->GetNumberOfComponents() != 2 ||
    !derivatives || derivatives->GetNumberOfComponents() != 3 * m ||
    derivatives->GetNumberOfTuples() != static_cast<vtkIdType>(region.localPositions.size()))
  {
    throw InvalidInputException(which + ": its design variables come without their values, bounds or derivatives (" +
      fields::PrescribedDerivatives + ", 3 per variable and point)");
  }
  for (vtkIdType v = 0; v < m; ++v)
  {
    region.variables.push_back(names->GetValue(v));
    region.values.push_back(values->GetTuple1(v));
    region.lower.push_back(bounds->GetComponent(v, 0));
    region.upper.push_back(bounds->GetComponent(v, 1));
  }
  region.derivatives = derivatives;
}
}

void readRegions(vtkInformationVector* connections, std::vector<RegionInput>& regions)
{
  regions.resize(connections->GetNumberOfInformationObjects());
  for (int c = 0; c < connections->GetNumberOfInformationObjects(); ++c)
  {
    vtkPolyData* data = vtkPolyData::GetData(connections, c);
    const std::string which = "Regions input #" + std::to_string(c);
    auto* role = data ? vtkIntArray::SafeDownCast(data->GetFieldData()->GetArray(fields::Role)) : nullptr;
    vtkDataArray* displacement = data ? data->GetPointData()->GetArray(fields::PrescribedDisplacement) : nullptr;
    auto* failed = data ? vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(fields::Error)) : nullptr;
    if (failed && failed->GetNumberOfValues() > 0)
    {
      auto* roleName = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(fields::RoleName));
      throw InvalidInputException(which + (roleName && roleName->GetNumberOfValues() > 0 ? " (" + roleName->GetValue(0) + ")" : "") +
        " failed: " + failed->GetValue(0));
    }
    if (!role || role->GetNumberOfValues() < 1 || !displacement || displacement->GetNumberOfComponents() != 3)
    {
      throw InvalidInputException(which + " is not a ConstraintRegion output (no Role or PrescribedDisplacement)");
    }
    RegionInput& region = regions[c];
    region.role = role->GetValue(0);
    if (region.role == roles::FromPrimitive || !regionRole(region.role).name) // regionRole throws for an unknown role
    {
      throw InvalidInputException(which + " has the role FromPrimitive, which a Constraint Region replaces by its primitive's role");
    }
    region.displacement = displacement;
    vtkFieldData* fieldData = data->GetFieldData();
    vtkDataArray* weight = fieldData->GetArray(fields::Weight);
    region.weight = weight ? weight->GetTuple1(0) : 1.0;
    vtkDataArray* dragging = fieldData->GetArray(fields::Dragging);
    region.dragging = dragging && dragging->GetNumberOfTuples() > 0 && dragging->GetTuple1(0) != 0;
    if (region.role == roles::Symmetric)
    {
      vtkDataArray* plane = fieldData->GetArray(fields::SymmetryPlane);
      const double* p = plane && plane->GetNumberOfComponents() == 6 && plane->GetNumberOfTuples() == 1 ? plane->GetTuple(0) : nullptr;
      const Vec3 normal = p ? Vec3(p[3], p[4], p[5]) : Vec3::Zero();
      if (!p || !Vec3(p[0], p[1], p[2]).allFinite() || !normal.allFinite() || !(normal.norm() > 0))
      {
        throw InvalidInputException(which + " (Symmetric) has no symmetry plane: SymmetryOrigin and a non-zero, finite SymmetryNormal");
      }
      region.mirror.point = Vec3(p[0], p[1], p[2]);
      region.mirror.normal = normal.normalized();
    }
    vtkDataArray* group = fieldData->GetArray(fields::ConstraintGroup);
    region.group = (region.role == roles::Coplanar || region.role == roles::Distance) && group ? static_cast<int>(group->GetTuple1(0)) : 0;
    vtkDataArray* axis = fieldData->GetArray(fields::DistanceAxis);
    region.axis = region.role == roles::Distance && axis && axis->GetNumberOfComponents() == 3 ? Vec3(axis->GetTuple3(0)) : Vec3::Zero();
    if (!region.axis.allFinite())
    {
      throw InvalidInputException(which + " (Distance) has an axis that is not finite");
    }
    vtkDataArray* bound = fieldData->GetArray(fields::MinimumDistance);
    region.minimumDistance = region.role == roles::Offset && bound ? bound->GetTuple1(0) : 0.0;
    if (region.role == roles::Offset)
    {
      vtkDataArray* triangles = fieldData->GetArray(fields::ReferenceTriangles);
      if (!triangles || triangles->GetNumberOfComponents() != 9 || !std::isfinite(region.minimumDistance))
      {
        throw InvalidInputException(which + " (Offset) has no reference surface (" + fields::ReferenceTriangles +
          ", 9 coordinates per triangle) or no finite " + fields::MinimumDistance);
      }
      // read again only when the region wrote a new one (not on every handle motion)
      if (triangles->GetMTime() != region.referenceTime)
      {
        region.localReference.resize(9 * static_cast<std::size_t>(triangles->GetNumberOfTuples()));
        for (vtkIdType t = 0; t < triangles->GetNumberOfTuples(); ++t)
        {
          triangles->GetTuple(t, region.localReference.data() + 9 * t);
        }
        region.referenceTime = triangles->GetMTime();
        region.localChanged = true;
      }
    }
    Stamp stamp = pointsStamp({ data });
    if (stamp != region.stamp)
    {
      PointList positions = points({ data });
      requireFinite(positions, (which + " positions").c_str());
      std::vector<int> sets;
      if (vtkDataArray* setArray = data->GetPointData()->GetArray(fields::ConstraintSet))
      {
        for (vtkIdType i = 0; i < setArray->GetNumberOfTuples(); ++i)
        {
          sets.push_back(static_cast<int>(setArray->GetTuple1(i)));
        }
      }
      if (!sets.empty() && sets.size() != positions.size())
      {
        throw InvalidInputException(which + ": one ConstraintSet per point is needed");
      }
      if (positions != region.localPositions || sets != region.localSets)
      {
        region.localPositions = std::move(positions);
        region.localSets = std::move(sets);
        region.localChanged = true;
      }
      region.stamp = std::move(stamp);
    }
    if (displacement->GetNumberOfTuples() != static_cast<vtkIdType>(region.localPositions.size()))
    {
      throw InvalidInputException(which + ": one PrescribedDisplacement per point is needed");
    }
    readDesignVariables(data, which, region);
  }
}

void gatherRegions(std::vector<RegionInput>& regions, long& nextVersion, const Collective& group)
{
  bool changed = false;
  for (const RegionInput& region : regions)
  {
    changed = changed || region.localChanged;
  }
  if (group.any(changed))
  {
    for (std::size_t c = 0; c < regions.size(); ++c)
    {
      RegionInput& region = regions[c];
      GatheredPositions gathered = gatherPositions(region.localPositions, region.localSets, group);
      bool changedValues = gathered.positions != region.gathered.positions || gathered.sets != region.gathered.sets || region.version < 0;
      if (region.role == roles::Offset)
      {
        std::vector<double> reference = group.gather(region.localReference);
        if (reference != region.gatheredReference || !region.reference)
        {
          PointList corners;
          for (std::size_t i = 0; i + 2 < reference.size(); i += 3)
          {
            corners.emplace_back(reference[i], reference[i + 1], reference[i + 2]);
          }
          try
          {
            region.reference = std::make_shared<ReferenceSurface>(std::move(corners));
          }
          catch (const InvalidInputException& e)
          {
            throw InvalidInputException("Regions input #" + std::to_string(c) + " (Offset): " + e.what());
          }
          region.gatheredReference = std::move(reference);
          changedValues = true;
        }
      }
      if (changedValues)
      {
        region.version = nextVersion++;
      }
      region.gathered = std::move(gathered);
      region.localChanged = false;
    }
  }
  bool handle = false;
  for (std::size_t c = 0; c < regions.size(); ++c)
  {
    if (regions[c].gathered.positions.empty())
    {
      throw InvalidInputException("Regions input #" + std::to_string(c) + " (" + regionRole(regions[c].role).name + ") selects no point");
    }
    handle = handle || regions[c].role == roles::Handle;
  }
  if (!handle)
  {
    throw InvalidInputException("no Handle region among the Regions inputs: nothing would move");
  }
}

void addConstraintSets(const RegionInput& region, std::vector<ShapeConstraint>& shapes)
{
  ShapeConstraint shape;
  shape.type = *regionRole(region.role).constraint;
  shape.weight = region.weight;
  shape.mirror = region.mirror;
  shape.group = region.group;
  shape.axis = region.axis;
  shape.minimumDistance = region.minimumDistance;
  shape.reference = region.reference;
  if (region.gathered.sets.empty())
  {
    shape.positions = region.gathered.positions;
    shapes.push_back(std::move(shape));
    return;
  }
  std::map<int, PointList> sets;
  for (std::size_t i = 0; i < region.gathered.positions.size(); ++i)
  {
    sets[region.gathered.sets[i]].push_back(region.gathered.positions[i]);
  }
  // a region's weight spread over its cells' sets by their size; a Slip region's sets are its
  // blocks (patches selected by name), each weighing as a region of its own
  const double share = region.weight / static_cast<double>(region.gathered.positions.size());
  for (auto& [id, positions] : sets)
  {
    shape.weight = shape.type == ConstraintType::Slip ? region.weight : share * static_cast<double>(positions.size());
    shape.positions = std::move(positions);
    shapes.push_back(shape);
  }
}

std::vector<PointDisplacementsView> gatherPrescribed(const std::vector<RegionInput>& regions, std::vector<std::vector<double>>& values,
  const Collective& group)
{
  std::vector<PointDisplacementsView> prescribed;
  values.resize(regions.size());
  for (std::size_t r = 0; r < regions.size(); ++r)
  {
    if (isConstraint(regions[r].role))
    {
      continue;
    }
    // this process's values, as doubles, then every process's in the regions' gathered order
    vtkDataArray* d = regions[r].displacement;
    const vtkIdType n = d->GetNumberOfTuples();
    std::vector<double> local;
    const double* given = nullptr;
    if (auto* doubles = vtkDoubleArray::SafeDownCast(d))
    {
      given = doubles->GetPointer(0);
    }
    else
    {
      local.resize(3 * static_cast<std::size_t>(n));
      for (vtkIdType i = 0; i < n; ++i)
      {
        d->GetTuple(i, &local[3 * i]);
      }
      given = local.data();
    }
    values[r] = gatherValues(given, n, 3, regions[r].gathered, group);
    prescribed.emplace_back(values[r].data(), static_cast<long>(regions[r].gathered.positions.size()), 3);
  }
  return prescribed;
}
} // namespace mlsvtk
