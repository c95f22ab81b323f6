#include "Adapters/ControlPoints.h"

#include "Adapters/MeshCells.h"
#include "Common/BoundingBox.h"
#include "Common/GatheredPositions.h"
#include "Common/KdTree.h"
#include "Common/PositionHash.h"

#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

using mlsdeform::InvalidInputException;
using mlsdeform::PointList;
using mlsdeform::Vec3;

namespace mlsvtk
{
namespace
{
struct ExactHash
{
  std::size_t operator()(const Vec3& x) const { return static_cast<std::size_t>(mlsdeform::positionKey(x)); }
};
template <typename Value>
using PositionMap = std::unordered_map<Vec3, Value, ExactHash>;
using PositionSet = std::unordered_set<Vec3, ExactHash>;

std::string text(const Vec3& x)
{
  return "(" + std::to_string(x.x()) + ", " + std::to_string(x.y()) + ", " + std::to_string(x.z()) + ")";
}

// x without its component along the unit axis (unchanged for a zero axis)
Vec3 across(const Vec3& x, const Vec3& axis)
{
  return x - x.dot(axis) * axis;
}

Vec3 unit(const Vec3& axis)
{
  return axis == Vec3::Zero() ? axis : Vec3(axis.normalized());
}

// Calls visit(corner positions) for every polygon of the surface: the 2D cells of the sets if
// any process has one, otherwise the boundary faces of their 3D cells (the rule of the sampling
// domain, MeshCells.h), each oriented out of the mesh.
template <typename Visit>
void visitSurface(const std::vector<vtkPointSet*>& sets, const mlsdeform::Collective& group, Visit visit)
{
  bool surfaceCells = false;
  for (vtkPointSet* set : sets)
  {
    for (vtkIdType c = 0; c < set->GetNumberOfCells() && !surfaceCells; ++c)
    {
      surfaceCells = cellDimension(set->GetCellType(c)) == 2;
    }
  }
  PointList corners;
  vtkNew<vtkIdList> ids;
  const auto polygon = [&](vtkPointSet* points, const vtkIdType* map) {
    corners.resize(static_cast<std::size_t>(ids->GetNumberOfIds()));
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      points->GetPoint(map ? map[ids->GetId(k)] : ids->GetId(k), corners[k].data());
    }
    visit(corners);
  };
  if (group.any(surfaceCells))
  {
    for (vtkPointSet* set : sets)
    {
      for (vtkIdType c = 0; c < set->GetNumberOfCells(); ++c)
      {
        if (cellDimension(set->GetCellType(c)) == 2)
        {
          set->GetCellPoints(c, ids);
          polygon(set, nullptr);
        }
      }
    }
    return;
  }
  const std::vector<BoundaryFaces> boundaries = boundaryFaces(sets, group);
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    if (vtkPolyData* faces = boundaries[s].faces)
    {
      for (vtkIdType f = 0; f < faces->GetNumberOfCells(); ++f)
      {
        faces->GetCellPoints(f, ids);
        polygon(faces, nullptr); // the faces' own points: the set's positions
      }
    }
  }
}

// The unit normals at the queries: the sum of the area vectors (Newell) of the surface polygons
// with a corner there and all corners in the region, summed in an order of the polygons' centroids
// (the same on any split over processes). Zero where there is no such polygon.
PointList surfaceNormals(const PointList& queries, const PositionSet& region, const std::vector<vtkPointSet*>& sets,
  const mlsdeform::Collective& group)
{
  PositionMap<int> index;
  for (std::size_t k = 0; k < queries.size(); ++k)
  {
    index.emplace(queries[k], static_cast<int>(k));
  }
  std::vector<double> records; // query, centroid, area vector: 7 each
  visitSurface(sets, group, [&](const PointList& corners) {
    bool touches = false, inside = true;
    for (const Vec3& x : corners)
    {
      touches = touches || index.count(x) > 0;
      inside = inside && region.count(x) > 0;
    }
    if (!touches || !inside || corners.size() < 3)
    {
      return;
    }
    Vec3 area = Vec3::Zero(), centroid = Vec3::Zero();
    for (std::size_t k = 0; k < corners.size(); ++k)
    {
      area += 0.5 * corners[k].cross(corners[(k + 1) % corners.size()]);
      centroid += corners[k] / static_cast<double>(corners.size());
    }
    for (const Vec3& x : corners)
    {
      const auto it = index.find(x);
      if (it != index.end())
      {
        records.insert(records.end(), { static_cast<double>(it->second), centroid.x(), centroid.y(), centroid.z(), area.x(),
                                        area.y(), area.z() });
      }
    }
  });
  const std::vector<double> all = group.gather(records);
  std::vector<std::array<double, 7>> sorted(all.size() / 7);
  for (std::size_t r = 0; r < sorted.size(); ++r)
  {
    std::copy(all.begin() + 7 * r, all.begin() + 7 * r + 7, sorted[r].begin());
  }
  std::sort(sorted.begin(), sorted.end());
  PointList normals(queries.size(), Vec3::Zero());
  for (const std::array<double, 7>& r : sorted)
  {
    normals[static_cast<std::size_t>(r[0])] += Vec3(r[4], r[5], r[6]);
  }
  return normals;
}
} // namespace

void checkControlPoints(const std::vector<ControlPoint>& controls, const std::vector<DesignVariable>& variables)
{
  for (const ControlPoint& c : controls)
  {
    const auto v = std::find_if(variables.begin(), variables.end(), [&](const DesignVariable& d) { return d.name == c.variable; });
    if (v == variables.end() || v->kind != Local)
    {
      throw InvalidInputException("a control point names '" + c.variable + "', which is not a Local design variable of this region");
    }
    if (!c.position.allFinite() || !c.direction.allFinite() || !c.lineAxis.allFinite())
    {
      throw InvalidInputException("a control point of '" + c.variable + "' has a coordinate that is not finite (NaN or infinity)");
    }
  }
  for (const DesignVariable& v : variables)
  {
    if (v.kind == Local &&
      std::none_of(controls.begin(), controls.end(), [&](const ControlPoint& c) { return c.variable == v.name; }))
    {
      throw InvalidInputException("the Local design variable '" + v.name + "' has no control point (ControlPoints)");
    }
  }
}

HeldPositions holdControlPoints(const std::vector<ControlPoint>& controls, const PointList& selected,
  const std::vector<vtkPointSet*>& sets, const mlsdeform::Collective& group)
{
  const PointList all = mlsdeform::gatherPositions(selected, {}, group).positions;
  if (controls.size() > all.size())
  {
    throw InvalidInputException(std::to_string(controls.size()) + " control points, but the region has only " +
      std::to_string(all.size()) + " points: give fewer");
  }
  const mlsdeform::KdTree tree(all);
  const mlsdeform::BoundingBox box = mlsdeform::boundingBox(all);
  const double tolerance = 1e-6 * (box.upper - box.lower).norm(); // on a line: extruded meshes' round-off
  HeldPositions held;
  PositionMap<int> owner;
  for (std::size_t c = 0; c < controls.size(); ++c)
  {
    const Vec3 q = all[static_cast<std::size_t>(tree.nearest(controls[c].position))];
    const Vec3 axis = unit(controls[c].lineAxis);
    // a given point far from the region is a mistake (another region's, other units), not a snap:
    // near is within a tenth of the region's size or two point spacings there (a coarse mesh's)
    const double off = (axis == Vec3::Zero() ? Vec3(q - controls[c].position) : across(q - controls[c].position, axis)).norm();
    std::vector<int> neighbours;
    std::vector<double> squared;
    tree.kNearest(q, 2, neighbours, squared);
    const double near = std::max(0.1 * (box.upper - box.lower).norm(), squared.size() > 1 ? 2 * std::sqrt(squared[1]) : 0.0);
    if (off > near)
    {
      throw InvalidInputException("the control point of '" + controls[c].variable + "' at " + text(controls[c].position) + " is " +
        std::to_string(off) + " from the region's nearest point " + text(q) + ", farther than a tenth of the region's size and " +
        "two point spacings there (" + std::to_string(near) + "): give points on or near the region");
    }
    held.snapped.push_back(q);
    for (const Vec3& x : all)
    {
      if (axis == Vec3::Zero() ? x == q : across(x - q, axis).norm() <= tolerance)
      {
        const auto [it, added] = owner.emplace(x, static_cast<int>(c));
        if (!added)
        {
          throw InvalidInputException("the control points of '" + controls[it->second].variable + "' and '" +
            controls[c].variable + "' both hold the region's point " + text(x) +
            ": control points must be apart (fewer of them, or other positions)");
        }
      }
    }
  }
  // directions: as given, or the outward normal across the line axis
  PointList queries;
  for (std::size_t c = 0; c < controls.size(); ++c)
  {
    if (controls[c].direction == Vec3::Zero())
    {
      queries.push_back(held.snapped[c]);
    }
  }
  const PointList normals =
    queries.empty() ? PointList() : surfaceNormals(queries, PositionSet(selected.begin(), selected.end()), sets, group);
  std::size_t query = 0;
  for (std::size_t c = 0; c < controls.size(); ++c)
  {
    if (controls[c].direction != Vec3::Zero())
    {
      const Vec3& d = controls[c].direction;
      if (controls[c].lineAxis != Vec3::Zero() && std::abs(d.dot(unit(controls[c].lineAxis))) > 1e-9 * d.norm())
      {
        throw InvalidInputException("the direction " + text(d) + " of '" + controls[c].variable + "' has a part along its line axis " +
          text(controls[c].lineAxis) + ": a control line moves across its axis only (the depth of a 2D case, a plate's thickness " +
          "stay as they are); give a direction normal to the axis");
      }
      held.directions.push_back(d);
      continue;
    }
    const Vec3 n = across(normals[query++], unit(controls[c].lineAxis));
    if (!(n.norm() > 0))
    {
      throw InvalidInputException("the control point of '" + controls[c].variable + "' at " + text(held.snapped[c]) +
        " has no surface normal: the region has no surface faces there (a point cloud, or faces outside the region)" +
        (controls[c].lineAxis == Vec3::Zero() ? "" : " or they face along the line axis") + "; give the variable a direction");
    }
    held.directions.push_back(n.normalized());
  }
  for (const Vec3& x : selected)
  {
    const auto it = owner.find(x);
    if (it != owner.end())
    {
      held.positions.push_back(x);
      held.control.push_back(it->second);
    }
  }
  return held;
}

PointList spreadControlPoints(const PointList& selected, int count, const Vec3& lineAxis, const mlsdeform::Collective& group)
{
  const PointList all = mlsdeform::gatherPositions(selected, {}, group).positions; // sorted: all[0] is the least
  const Vec3 axis = unit(lineAxis);
  if (count < 1 || all.empty())
  {
    throw InvalidInputException("spreading " + std::to_string(count) + " control points over a region of " +
      std::to_string(all.size()) + " points: both must be at least 1");
  }
  std::vector<double> distance(all.size(), std::numeric_limits<double>::infinity());
  PointList picked;
  std::size_t next = 0;
  while (static_cast<int>(picked.size()) < count)
  {
    if (!picked.empty() && !(distance[next] > 0))
    {
      throw InvalidInputException(std::to_string(count) + " control points, but the region has only " +
        std::to_string(picked.size()) + (axis == Vec3::Zero() ? " points" : " lines along the axis") + ": give fewer");
    }
    picked.push_back(all[next]);
    const Vec3 p = across(all[next], axis);
    next = 0;
    for (std::size_t i = 0; i < all.size(); ++i)
    {
      distance[i] = std::min(distance[i], (across(all[i], axis) - p).squaredNorm());
      next = distance[i] > distance[next] ? i : next; // the first of the farthest
    }
  }
  return picked;
}
} // namespace mlsvtk
