#include "vtkConstraintRegion.h"

#include "Common/BoundingBox.h"
#include "Adapters/BlockSelection.h"
#include "Adapters/FailurePolicy.h"
#include "Adapters/ControlPoints.h"
#include "Adapters/DesignVariables.h"
#include "Adapters/HandleMotion.h"
#include "Common/KdTree.h"
#include "Common/GatheredPositions.h"
#include "Adapters/PointSets.h"
#include "Adapters/MeshCells.h"
#include "Adapters/Stamp.h"
#include "Common/PositionHash.h"
#include "Adapters/ProcessCollective.h"
#include "Adapters/ReportArrays.h"
#include "Vocabulary/FieldNames.h"
#include "Vocabulary/RegionRoles.h"

#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkImplicitFunction.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <unordered_set>


vtkStandardNewMacro(vtkConstraintRegion);

// The class's enum (wrapped for Python) has the values of the table of roles.
static_assert(vtkConstraintRegion::Handle == mlsvtk::roles::Handle && vtkConstraintRegion::Fixed == mlsvtk::roles::Fixed &&
    vtkConstraintRegion::Planarity == mlsvtk::roles::Planarity && vtkConstraintRegion::Circularity == mlsvtk::roles::Circularity &&
    vtkConstraintRegion::Cylinder == mlsvtk::roles::Cylinder && vtkConstraintRegion::FeatureLine == mlsvtk::roles::FeatureLine &&
    vtkConstraintRegion::Rigid == mlsvtk::roles::Rigid && vtkConstraintRegion::FromPrimitive == mlsvtk::roles::FromPrimitive &&
    vtkConstraintRegion::Slip == mlsvtk::roles::Slip && vtkConstraintRegion::Symmetric == mlsvtk::roles::Symmetric &&
    vtkConstraintRegion::Coplanar == mlsvtk::roles::Coplanar && vtkConstraintRegion::Distance == mlsvtk::roles::Distance &&
    vtkConstraintRegion::Offset == mlsvtk::roles::Offset && vtkConstraintRegion::Offset + 1 == mlsvtk::roles::Table.size(),
  "vtkConstraintRegion::Roles follows mlsvtk::roles");

static_assert(vtkConstraintRegion::TranslateVariable == mlsvtk::Translate && vtkConstraintRegion::RotateVariable == mlsvtk::Rotate &&
    vtkConstraintRegion::ScaleVariable == mlsvtk::Scale && vtkConstraintRegion::LocalVariable == mlsvtk::Local &&
    std::size(mlsvtk::DesignKindNames) == 4,
  "vtkConstraintRegion::DesignVariableKinds follows mlsvtk::DesignKind");

namespace
{
// The point rules: a point inside the function (mode ImplicitFunction), with its value within
// range (mode ArrayRange) or with primitive among the components of its value (mode Primitive;
// a set without the array has none), or any point (mode AllPoints).
struct PointRule
{
  int mode = vtkConstraintRegion::AllPoints;
  vtkImplicitFunction* function = nullptr;
  bool insideOut = false;
  const double* range = nullptr;
  int primitive = 0;

  bool selects(vtkPointSet* set, vtkDataArray* values, vtkIdType i) const
  {
    if ((mode == vtkConstraintRegion::ArrayRange || mode == vtkConstraintRegion::Primitive) && !values)
    {
      return false;
    }
    if (mode == vtkConstraintRegion::ImplicitFunction)
    {
      double x[3];
      set->GetPoint(i, x);
      return (function->FunctionValue(x) <= 0) != insideOut;
    }
    if (mode == vtkConstraintRegion::ArrayRange)
    {
      const double v = values->GetComponent(i, 0);
      return v >= range[0] && v <= range[1];
    }
    if (mode == vtkConstraintRegion::Primitive)
    {
      for (int c = 0; c < values->GetNumberOfComponents(); ++c)
      {
        if (values->GetComponent(i, c) == primitive)
        {
          return true;
        }
      }
      return false;
    }
    return true;
  }
};

// Why rule selected no point of sets, for the warning: where the points lie and what the rule saw
// at them, over every process: the Region function's least value (it selects where it is <= 0;
// with InsideOut its greatest, it selects where it is > 0), or the selection array's values.
std::string whyNoPoint(const PointRule& rule, const std::vector<vtkPointSet*>& sets, const std::vector<vtkDataArray*>& values,
  const mlsdeform::Collective& group)
{
  constexpr double none = -std::numeric_limits<double>::infinity();
  // maxima over the processes of -least and greatest: x, y, z, the function, the array's values
  std::vector<double> extremes(10, none);
  const auto widen = [&](int at, double value) {
    extremes[at] = std::max(extremes[at], -value);
    extremes[at + 1] = std::max(extremes[at + 1], value);
  };
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    for (vtkIdType i = 0; i < sets[s]->GetNumberOfPoints(); ++i)
    {
      double x[3];
      sets[s]->GetPoint(i, x);
      for (int c = 0; c < 3; ++c)
      {
        widen(2 * c, x[c]);
      }
      if (rule.mode == vtkConstraintRegion::ImplicitFunction)
      {
        widen(6, rule.function->FunctionValue(x));
      }
      if (rule.mode == vtkConstraintRegion::ArrayRange && values[s])
      {
        widen(8, values[s]->GetComponent(i, 0));
      }
    }
  }
  group.maximum(extremes);
  std::ostringstream why;
  why << "the input's points lie within x [" << -extremes[0] << ", " << extremes[1] << "], y [" << -extremes[2] << ", "
      << extremes[3] << "], z [" << -extremes[4] << ", " << extremes[5] << "]";
  if (rule.mode == vtkConstraintRegion::ImplicitFunction)
  {
    why << (rule.insideOut ? "; the Region function is at most " : "; the Region function is at least ")
        << (rule.insideOut ? extremes[7] : -extremes[6])
        << (rule.insideOut ? " at them (with InsideOut it selects where it is > 0)" : " at them (it selects where it is <= 0)");
  }
  if (rule.mode == vtkConstraintRegion::ArrayRange)
  {
    if (extremes[9] == none)
    {
      why << "; none of them has the selection array";
    }
    else
    {
      why << "; the selection array's values lie within [" << -extremes[8] << ", " << extremes[9] << "], and Range is ["
          << rule.range[0] << ", " << rule.range[1] << "]";
    }
  }
  return why.str();
}

// Positions compared exactly (the same point in two blocks or on two processes has the same
// coordinates: they come from the same file).
struct PositionKey
{
  std::size_t operator()(const mlsdeform::Vec3& x) const { return static_cast<std::size_t>(mlsdeform::positionKey(x)); }
};
using PositionSet = std::unordered_set<mlsdeform::Vec3, PositionKey>;

// The cells of the sets within `layers` cell layers of the surface's points (those within
// tolerance of a point of a set): layer 1 holds the cells with such a point, layer n + 1 the cells
// that share a point with layer n. A point reached in one set (or on one process) is reached in
// every set and on every process that holds its position, so that layers cross blocks and pieces.
std::vector<std::vector<char>> cellLayers(const std::vector<vtkPointSet*>& sets, const mlsdeform::KdTree& surface,
  const mlsdeform::PointList& surfacePoints, double tolerance, int layers, const mlsdeform::Collective& group)
{
  std::vector<std::vector<char>> reached(sets.size()), cells(sets.size());
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    vtkPointSet* set = sets[s];
    reached[s].assign(set->GetNumberOfPoints(), 0);
    cells[s].assign(set->GetNumberOfCells(), 0);
    for (vtkIdType i = 0; i < set->GetNumberOfPoints() && !surfacePoints.empty(); ++i)
    {
      mlsdeform::Vec3 x;
      set->GetPoint(i, x.data());
      reached[s][i] = (surfacePoints[surface.nearest(x)] - x).norm() <= tolerance;
    }
  }
  vtkNew<vtkIdList> ids;
  for (int layer = 0; layer < layers; ++layer)
  {
    // the next layer's cells; the positions they newly reach, from every set and process
    std::vector<double> newly;
    std::vector<std::vector<char>> next = reached;
    for (std::size_t s = 0; s < sets.size(); ++s)
    {
      vtkPointSet* set = sets[s];
      for (vtkIdType c = 0; c < set->GetNumberOfCells(); ++c)
      {
        if (cells[s][c])
        {
          continue;
        }
        set->GetCellPoints(c, ids);
        for (vtkIdType k = 0; k < ids->GetNumberOfIds() && !cells[s][c]; ++k)
        {
          cells[s][c] = reached[s][ids->GetId(k)];
        }
        for (vtkIdType k = 0; cells[s][c] && k < ids->GetNumberOfIds(); ++k)
        {
          const vtkIdType i = ids->GetId(k);
          if (!next[s][i])
          {
            next[s][i] = 1;
            double x[3];
            set->GetPoint(i, x);
            newly.insert(newly.end(), x, x + 3);
          }
        }
      }
    }
    if (layer + 1 == layers)
    {
      break;
    }
    const std::vector<double> all = group.gather(newly);
    PositionSet positions;
    for (std::size_t i = 0; i < all.size(); i += 3)
    {
      positions.insert(mlsdeform::Vec3(all[i], all[i + 1], all[i + 2]));
    }
    for (std::size_t s = 0; s < sets.size(); ++s)
    {
      for (vtkIdType i = 0; i < sets[s]->GetNumberOfPoints() && !positions.empty(); ++i)
      {
        mlsdeform::Vec3 x;
        sets[s]->GetPoint(i, x.data());
        next[s][i] = next[s][i] || positions.count(x) > 0;
      }
    }
    reached = std::move(next);
  }
  return cells;
}

// What a region selects: positions, and with cell sets the set of each position.
struct SelectedPositions
{
  mlsdeform::PointList positions;
  std::vector<double> sets; // empty: one set
};

// Points of the sets by the point rule, or (cell-based) the points of the chosen cells: each
// cell's points in turn with its set number (cellSets), or each point of a chosen cell once.
// Cells are chosen by layers around the surface (mode CellLayers) or when all their points
// follow the rule; with cell sets only cells of dimension 2 or 3 count.
// A Slip region's planes: each block selected whole is one (numbered by its composite id), and each
// entry that names set arrays one more (numbered from SetArrayPlanes by the entry's position).
constexpr int SetArrayPlanes = 1 << 24;

SelectedPositions selectPositions(const std::vector<vtkPointSet*>& sets, const std::vector<vtkDataArray*>& values,
  const PointRule& rule, bool cellSets, const mlsdeform::PointList& surface, int layers, const mlsvtk::BlockSelection* blocks,
  bool setPerBlock, int entry, const mlsdeform::Collective& group)
{
  SelectedPositions out;
  const bool byLayers = rule.mode == vtkConstraintRegion::CellLayers;
  std::vector<std::vector<char>> layerCells;
  if (byLayers)
  {
    mlsdeform::KdTree surfaceTree;
    surfaceTree.build(surface);
    // a patch and the mesh share their points up to float round-off (1e-7 relative of the
    // diagonal of all processes' points)
    std::optional<mlsdeform::BoundingBox> local;
    for (vtkPointSet* set : sets)
    {
      if (set->GetNumberOfPoints() > 0)
      {
        const double* b = set->GetBounds();
        const mlsdeform::Vec3 lower(b[0], b[2], b[4]), upper(b[1], b[3], b[5]);
        local = local ? mlsdeform::BoundingBox{ local->lower.cwiseMin(lower), local->upper.cwiseMax(upper) } : mlsdeform::BoundingBox{ lower, upper };
      }
    }
    const double diagonal = mlsdeform::boundingBox(local ? &*local : nullptr, group).size().norm();
    layerCells = cellLayers(sets, surfaceTree, surface, 1e-6 * diagonal, layers, group);
  }
  vtkNew<vtkIdList> ids;
  double cellSet = 0; // the set number of the next cell (cellSets)
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    vtkPointSet* set = sets[s];
    std::vector<char> chosen(set->GetNumberOfPoints());
    if (!byLayers)
    {
      for (vtkIdType i = 0; i < set->GetNumberOfPoints(); ++i)
      {
        chosen[i] = blocks ? blocks->points[s][i] : rule.selects(set, values[s], i);
      }
      if (!cellSets)
      {
        for (vtkIdType i = 0; i < set->GetNumberOfPoints(); ++i)
        {
          if (chosen[i])
          {
            out.positions.emplace_back();
            set->GetPoint(i, out.positions.back().data());
            if (setPerBlock)
            {
              // each block its own set (a Slip region's planes), numbered alike on every process
              // (negative: Common/GatheredPositions.h); the points of an entry's set arrays one more
              out.sets.push_back(-1.0 - (blocks->block[s] ? blocks->block[s] : SetArrayPlanes + entry));
            }
          }
        }
        continue;
      }
    }
    std::vector<char> used(set->GetNumberOfPoints(), 0);
    vtkUnsignedCharArray* ghosts = set->GetCellGhostArray();
    for (vtkIdType c = 0; c < set->GetNumberOfCells(); ++c)
    {
      if (ghosts && (ghosts->GetValue(c) & vtkDataSetAttributes::DUPLICATECELL))
      {
        continue; // another process's cell, selected there
      }
      set->GetCellPoints(c, ids);
      bool take = byLayers ? layerCells[s][c] != 0 : ids->GetNumberOfIds() > 0;
      for (vtkIdType k = 0; take && !byLayers && k < ids->GetNumberOfIds(); ++k)
      {
        take = chosen[ids->GetId(k)];
      }
      if (!take || (cellSets && mlsvtk::cellDimension(set->GetCellType(c)) < 2))
      {
        continue;
      }
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        if (cellSets)
        {
          out.positions.emplace_back();
          set->GetPoint(ids->GetId(k), out.positions.back().data());
          out.sets.push_back(cellSet);
        }
        else
        {
          used[ids->GetId(k)] = 1;
        }
      }
      cellSet += 1;
    }
    for (vtkIdType i = 0; !cellSets && i < set->GetNumberOfPoints(); ++i)
    {
      if (used[i])
      {
        out.positions.emplace_back();
        set->GetPoint(i, out.positions.back().data());
      }
    }
  }
  return out;
}
}
vtkCxxSetObjectMacro(vtkConstraintRegion, Region, vtkImplicitFunction);

// What a selection depends on: the selection properties (exact values) and the stamps of the
// input points, the selection arrays and the region function.
struct SelectionInputs
{
  int mode = -1;
  bool insideOut = false;
  double range[2] = { 0, 0 };
  int primitive = -1;
  int layers = 0;
  bool cellSets = false;
  std::vector<std::string> blocks; // mode Blocks
  bool setPerBlock = false;        // mode Blocks, role Slip
  mlsvtk::Stamp stamp;
  bool operator==(const SelectionInputs& o) const
  {
    return mode == o.mode && insideOut == o.insideOut && range[0] == o.range[0] && range[1] == o.range[1] &&
      primitive == o.primitive && layers == o.layers && cellSets == o.cellSets && blocks == o.blocks &&
      setPerBlock == o.setPerBlock && stamp == o.stamp;
  }
};

// The selected positions, what they were selected with, and the output arrays kept from update
// to update: while only the motion or the weight changes, the output shares the same point
// cloud (so a deformation downstream knows by its stamp that the positions did not change)
// and its displacement array is written again when no one else holds it.
struct vtkConstraintRegion::Selection
{
  SelectionInputs inputs;
  bool valid = false;
  mlsdeform::PointList positions; // this process's
  std::vector<double> sets;
  mlsdeform::Vec3 centroid = mlsdeform::Vec3::Zero(); // of all processes' positions, each once
  bool selectedAnywhere = false;
  vtkSmartPointer<vtkPolyData> cloud;
  vtkSmartPointer<vtkDoubleArray> displacement;
};

struct vtkConstraintRegion::DesignVariableList
{
  std::vector<mlsvtk::DesignVariable> variables;
  std::vector<mlsvtk::ControlPoint> controls;
  // the positions the controls hold, kept while the selection and the controls stay
  std::vector<mlsvtk::ControlPoint> heldControls;
  int heldSelection = -1;
  mlsvtk::HeldPositions held;
  vtkSmartPointer<vtkPolyData> heldCloud;
};

vtkConstraintRegion::vtkConstraintRegion()
  : Selected(std::make_unique<Selection>())
  , Designs(std::make_unique<DesignVariableList>())
{
  this->SetNumberOfInputPorts(2);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
  this->SetProgressText("Constraint Region");
}

vtkConstraintRegion::~vtkConstraintRegion()
{
  this->SetRegion(nullptr);
}

const char* vtkConstraintRegion::GetRoleName(int role)
{
  // a name getter (also for printing a bad value): no table row, no name
  return role >= 0 && role < static_cast<int>(mlsvtk::roles::Table.size()) ? mlsvtk::roles::Table[role].name : "Unknown";
}

void vtkConstraintRegion::SetSelectionArray(const char* name)
{
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, name);
}

void vtkConstraintRegion::AddDesignVariable(
  const char* name, int kind, double ax, double ay, double az, double value, double lower, double upper)
{
  mlsvtk::DesignVariable variable;
  variable.name = name ? name : "";
  variable.kind = kind;
  variable.axis = mlsdeform::Vec3(ax, ay, az);
  variable.value = value;
  variable.lower = lower;
  variable.upper = upper;
  this->Designs->variables.push_back(variable); // checked by RequestData: a bad one is reported there
  this->Modified();
}

void vtkConstraintRegion::RemoveAllDesignVariables()
{
  if (!this->Designs->variables.empty())
  {
    this->Designs->variables.clear();
    this->Modified();
  }
}

void vtkConstraintRegion::AddControlPoint(
  const char* variable, double px, double py, double pz, double dx, double dy, double dz, double ax, double ay, double az)
{
  mlsvtk::ControlPoint control;
  control.variable = variable ? variable : "";
  control.position = mlsdeform::Vec3(px, py, pz);
  control.direction = mlsdeform::Vec3(dx, dy, dz);
  control.lineAxis = mlsdeform::Vec3(ax, ay, az);
  this->Designs->controls.push_back(control); // checked by RequestData
  this->Modified();
}

void vtkConstraintRegion::RemoveAllControlPoints()
{
  if (!this->Designs->controls.empty())
  {
    this->Designs->controls.clear();
    this->Modified();
  }
}

int vtkConstraintRegion::GetNumberOfControlPoints()
{
  return static_cast<int>(this->Designs->controls.size());
}

const char* vtkConstraintRegion::GetControlPointVariable(int i)
{
  return i >= 0 && i < this->GetNumberOfControlPoints() ? this->Designs->controls[i].variable.c_str() : nullptr;
}

void vtkConstraintRegion::GetControlPoint(int i, double row[9])
{
  if (i < 0 || i >= this->GetNumberOfControlPoints())
  {
    return;
  }
  const mlsvtk::ControlPoint& c = this->Designs->controls[i];
  for (int k = 0; k < 3; ++k)
  {
    row[k] = c.position[k];
    row[3 + k] = c.direction[k];
    row[6 + k] = c.lineAxis[k];
  }
}

bool vtkConstraintRegion::SpreadControlPoints(int count, double ax, double ay, double az, vtkDoubleArray* out)
{
  const mlsvtk::ProcessCollective group;
  this->ControlPointError.clear();
  try
  {
    if (!out)
    {
      throw mlsdeform::InvalidInputException("SpreadControlPoints needs an output array");
    }
    const mlsdeform::Vec3 axis(ax, ay, az);
    if (!axis.allFinite())
    {
      throw mlsdeform::InvalidInputException("the line axis must be finite");
    }
    if (!group.any(this->Selected->valid))
    {
      throw mlsdeform::InvalidInputException("the region has no selection yet: update it first");
    }
    const mlsdeform::PointList picked = mlsvtk::spreadControlPoints(this->Selected->positions, count, axis, group);
    out->SetNumberOfComponents(3);
    out->SetNumberOfTuples(static_cast<vtkIdType>(picked.size()));
    for (std::size_t i = 0; i < picked.size(); ++i)
    {
      out->SetTuple(static_cast<vtkIdType>(i), picked[i].data());
    }
    return true;
  }
  catch (const std::exception& e)
  {
    this->ControlPointError = e.what();
    return false;
  }
}

const char* vtkConstraintRegion::GetControlPointError()
{
  return this->ControlPointError.c_str();
}

void vtkConstraintRegion::AddBlock(const char* entry)
{
  this->BlockNames.emplace_back(entry ? entry : "");
  this->Modified();
}

void vtkConstraintRegion::RemoveAllBlocks()
{
  if (!this->BlockNames.empty())
  {
    this->BlockNames.clear();
    this->Modified();
  }
}

void vtkConstraintRegion::AddSet(const char* name)
{
  this->SetNames.emplace_back(name ? name : "");
  this->Modified();
}

void vtkConstraintRegion::RemoveAllSets()
{
  if (!this->SetNames.empty())
  {
    this->SetNames.clear();
    this->Modified();
  }
}

std::vector<std::string> vtkConstraintRegion::SelectedNames() const
{
  std::vector<std::string> names = this->BlockNames;
  names.insert(names.end(), this->SetNames.begin(), this->SetNames.end());
  return names;
}

bool vtkConstraintRegion::NamesBlock(const char* entry, const char* name)
{
  return entry && name && mlsvtk::namesBlock(entry, name);
}

bool vtkConstraintRegion::NamesGroup(const char* entry, const char* group)
{
  return entry && group && mlsvtk::namesGroup(entry, group);
}

int vtkConstraintRegion::GetNumberOfSelectedBlocks()
{
  return static_cast<int>(this->SelectedBlocks.size());
}

const char* vtkConstraintRegion::GetSelectedBlockName(int i)
{
  return i >= 0 && i < this->GetNumberOfSelectedBlocks() ? this->SelectedBlocks[i].c_str() : nullptr;
}

int vtkConstraintRegion::GetNumberOfBlocks()
{
  return static_cast<int>(this->BlockNames.size());
}

const char* vtkConstraintRegion::GetBlock(int i)
{
  return i >= 0 && i < this->GetNumberOfBlocks() ? this->BlockNames[i].c_str() : nullptr;
}

int vtkConstraintRegion::GetNumberOfDesignVariables()
{
  return static_cast<int>(this->Designs->variables.size());
}

const char* vtkConstraintRegion::GetDesignVariableName(int i)
{
  return i >= 0 && i < this->GetNumberOfDesignVariables() ? this->Designs->variables[i].name.c_str() : nullptr;
}

void vtkConstraintRegion::GetDesignVariable(int i, double row[7])
{
  if (i < 0 || i >= this->GetNumberOfDesignVariables())
  {
    return;
  }
  const mlsvtk::DesignVariable& v = this->Designs->variables[i];
  const double values[7] = { static_cast<double>(v.kind), v.axis.x(), v.axis.y(), v.axis.z(), v.value, v.lower, v.upper };
  std::copy(values, values + 7, row);
}

vtkMTimeType vtkConstraintRegion::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  if (this->Region)
  {
    time = std::max(time, this->Region->GetMTime());
  }
  return time;
}

int vtkConstraintRegion::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1); // the Surface of mode CellLayers
  }
  return 1;
}

// What a selection reads: the input's point sets, the Surface input's (mode CellLayers) and the
// selection array of each set (modes ArrayRange and Primitive).
struct vtkConstraintRegion::Inputs
{
  vtkDataObject* data = nullptr; // the input, a composite or one point set
  std::vector<vtkPointSet*> sets, surfaceSets;
  std::vector<vtkDataArray*> values;
};

int vtkConstraintRegion::RequestData(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const mlsvtk::ReportArrays reports(inputVector[0], outputVector); // its field data: reports, not fields
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  // Split over processes, each selects from its own piece; what depends on the whole selection
  // (the pivot, the layers around a surface) is computed over all of them.
  const mlsvtk::ProcessCollective group;
  this->SetErrorCode(vtkErrorCode::NoError);
  try
  {
    Inputs in;
    in.data = input;
    in.sets = mlsvtk::pointSets(input);
    vtkDataObject* surfaceInput = this->GetNumberOfInputConnections(1) > 0 ? vtkDataObject::GetData(inputVector[1], 0) : nullptr;
    in.surfaceSets = surfaceInput ? mlsvtk::pointSets(surfaceInput) : std::vector<vtkPointSet*>();
    for (vtkPointSet* set : in.sets)
    {
      in.values.push_back(this->SelectionMode == ArrayRange ? this->GetInputArrayToProcess(0, set)
          : this->SelectionMode == Primitive           ? set->GetPointData()->GetArray(mlsvtk::fields::PrimitiveIds)
                                                       : nullptr);
    }
    const int role = this->CheckedRole(in, group);
    this->UpdateSelection(in, group); // unless only the motion or the weight changed since the last selection
    if (!this->Selected->selectedAnywhere && group.any(input->GetNumberOfElements(vtkDataObject::POINT) > 0))
    {
      const PointRule rule{ this->SelectionMode, this->Region, this->InsideOut, this->Range, this->PrimitiveId };
      const std::string why = whyNoPoint(rule, in.sets, in.values, group); // on every process
      if (group.rank() == 0)
      {
        vtkWarningMacro(<< GetRoleName(role) << " region selects no point: " << why << ".");
      }
    }
    this->WriteOutput(output, role, in, group);
  }
  catch (const std::exception& e)
  {
    output->Initialize();
    this->SetErrorCode(vtkErrorCode::UserError);
    mlsvtk::reportFailure(this, outputVector, e, "The output is empty.");
    // the role it was given, so that MLS Deform names the region that failed by it
    vtkNew<vtkStringArray> roleName;
    roleName->SetName(mlsvtk::fields::RoleName);
    roleName->InsertNextValue(GetRoleName(this->Role));
    output->GetFieldData()->AddArray(roleName);
    return 1;
  }
  return 1;
}

int vtkConstraintRegion::CheckedRole(const Inputs& in, const mlsdeform::Collective& group)
{
  if (this->SelectionMode == ImplicitFunction && !this->Region)
  {
    throw mlsdeform::InvalidInputException("SelectionMode is ImplicitFunction but no Region function is set");
  }

  if (this->SelectionMode == Blocks && this->BlockNames.empty() && this->SetNames.empty())
  {
    throw mlsdeform::InvalidInputException("SelectionMode Blocks needs the names of what it selects in Blocks (patches, "
                                           "patch groups, sets, or blocks ticked in the panel's list) or Sets");
  }
  if (this->Role == FromPrimitive && this->SelectionMode != Primitive)
  {
    throw mlsdeform::InvalidInputException("Role FromPrimitive needs SelectionMode Primitive (a Primitive Detector's output as input)");
  }
  std::vector<std::int64_t> surfacePoints{ 0 };
  for (vtkPointSet* set : in.surfaceSets)
  {
    surfacePoints[0] += set->GetNumberOfPoints();
  }
  group.sum(surfacePoints);
  if (this->SelectionMode == CellLayers && surfacePoints[0] == 0)
  {
    throw mlsdeform::InvalidInputException("SelectionMode CellLayers needs a Surface input with points (e.g. the wall patch whose layer cells are selected)");
  }
  if (this->Role == Offset && surfacePoints[0] == 0)
  {
    throw mlsdeform::InvalidInputException("Role Offset needs a Surface input: the fixed reference surface its points keep their distance from");
  }
  int role = this->Role;
  std::string problem; // a check on this process's data: every process stops if one fails
  if (this->SelectionMode == Primitive)
  {
    // the primitive must exist in the detector's output; its type gives the FromPrimitive role
    vtkDataArray* types = nullptr;
    for (vtkPointSet* set : in.sets)
    {
      types = types ? types : set->GetFieldData()->GetArray(mlsvtk::fields::PrimitiveTypes);
    }
    if (!types)
    {
      problem = "SelectionMode Primitive needs a Primitive Detector's output as input (field data PrimitiveTypes and "
                "point array PrimitiveIds are missing).";
    }
    else if (this->PrimitiveId >= types->GetNumberOfTuples())
    {
      problem = "There is no primitive " + std::to_string(this->PrimitiveId) + ": the detector found " +
        std::to_string(types->GetNumberOfTuples()) + " (ids 0 to " + std::to_string(types->GetNumberOfTuples() - 1) + ").";
    }
    else if (this->Role == FromPrimitive)
    {
      // the detector's code: a value of mlsdeform::PrimitiveType (Plane first, Cone last)
      const double code = types->GetComponent(this->PrimitiveId, 0);
      const int type = static_cast<int>(code);
      if (type != code || type < static_cast<int>(mlsdeform::PrimitiveType::Plane) || type > static_cast<int>(mlsdeform::PrimitiveType::Cone))
      {
        problem = "Primitive " + std::to_string(this->PrimitiveId) + " has an unknown type " + std::to_string(code) + ".";
      }
      else
      {
        role = mlsvtk::roleOfPrimitive(static_cast<mlsdeform::PrimitiveType>(type));
      }
    }
  }
  problem = group.firstError(problem);
  if (!problem.empty())
  {
    throw mlsdeform::InvalidInputException(problem);
  }
  if (!this->Designs->variables.empty() && role != Handle)
  {
    throw mlsdeform::InvalidInputException(std::string("design variables act on a Handle region's motion; this region is ") +
      GetRoleName(role) + " (remove its design variables or make it a Handle)");
  }
  mlsvtk::checkDesignVariables(this->Designs->variables);
  mlsvtk::checkControlPoints(this->Designs->controls, this->Designs->variables);
  // a shape constraint per cell: the constraint roles that keep shapes, not places (measuresPlaces)
  const auto perCell = [](int r) { return mlsvtk::isConstraint(r) && !mlsdeform::measuresPlaces(*mlsvtk::regionRole(r).constraint); };
  if (this->CellSets && !perCell(role))
  {
    std::string roles;
    for (int r = 0; r < static_cast<int>(mlsvtk::roles::Table.size()); ++r)
    {
      if (perCell(r))
      {
        roles += (roles.empty() ? "" : ", ") + std::string(GetRoleName(r));
      }
    }
    throw mlsdeform::InvalidInputException(
      "CellSets makes a constraint set of every cell: it applies to the roles " + roles + ", not to " + GetRoleName(role));
  }
  return role;
}

void vtkConstraintRegion::UpdateSelection(const Inputs& in, const mlsdeform::Collective& group)
{
  SelectionInputs inputs;
  inputs.mode = this->SelectionMode;
  inputs.insideOut = this->InsideOut;
  inputs.range[0] = this->Range[0];
  inputs.range[1] = this->Range[1];
  inputs.primitive = this->PrimitiveId;
  const bool byCells = this->CellSets || this->SelectionMode == CellLayers;
  inputs.layers = this->SelectionMode == CellLayers ? this->NumberOfLayers : 0;
  inputs.cellSets = this->CellSets;
  inputs.blocks = this->SelectionMode == Blocks ? this->SelectedNames() : std::vector<std::string>();
  inputs.setPerBlock = this->SelectionMode == Blocks && this->Role == Slip && !this->CellSets;
  inputs.stamp = mlsvtk::pointsStamp(in.sets);
  if (byCells || this->SelectionMode == Blocks) // (a cell set array selects its cells' points)
  {
    for (const mlsvtk::Stamp& more : { mlsvtk::cellsStamp(in.sets), mlsvtk::pointsStamp(in.surfaceSets) })
    {
      inputs.stamp.objects.insert(inputs.stamp.objects.end(), more.objects.begin(), more.objects.end());
    }
  }
  inputs.stamp.add(this->Region);
  for (vtkDataArray* array : in.values)
  {
    inputs.stamp.add(array);
  }
  Selection& selection = *this->Selected;
  if (group.any(!selection.valid || !(inputs == selection.inputs)))
  {
    selection.valid = false;
    const PointRule rule{ this->SelectionMode, this->Region, this->InsideOut, this->Range, this->PrimitiveId };
    // the surface's points of all processes
    const mlsdeform::PointList surface = this->SelectionMode == CellLayers
      ? mlsdeform::gatherPositions(mlsvtk::points(in.surfaceSets), {}, group).positions
      : mlsdeform::PointList();
    this->SelectedBlocks.clear();
    SelectedPositions chosen;
    if (inputs.setPerBlock)
    {
      // a Slip region: each entry selected on its own, so that each names its own planes (a point
      // of two, on an edge, slides along both)
      const std::vector<std::string> names = this->SelectedNames();
      for (std::size_t e = 0; e < names.size(); ++e)
      {
        const mlsvtk::BlockSelection blocks = mlsvtk::selectBlocks(in.data, in.sets, { names[e] }, group);
        SelectedPositions part = selectPositions(in.sets, in.values, rule, this->CellSets, surface, this->NumberOfLayers,
          &blocks, true, static_cast<int>(e), group);
        chosen.positions.insert(chosen.positions.end(), part.positions.begin(), part.positions.end());
        chosen.sets.insert(chosen.sets.end(), part.sets.begin(), part.sets.end());
        for (const std::string& block : blocks.names)
        {
          if (std::find(this->SelectedBlocks.begin(), this->SelectedBlocks.end(), block) == this->SelectedBlocks.end())
          {
            this->SelectedBlocks.push_back(block);
          }
        }
      }
    }
    else
    {
      const std::optional<mlsvtk::BlockSelection> blocks = this->SelectionMode == Blocks
        ? std::optional<mlsvtk::BlockSelection>(mlsvtk::selectBlocks(in.data, in.sets, this->SelectedNames(), group))
        : std::nullopt;
      chosen = selectPositions(in.sets, in.values, rule, this->CellSets, surface, this->NumberOfLayers,
        blocks ? &*blocks : nullptr, false, 0, group);
      this->SelectedBlocks = blocks ? blocks->names : std::vector<std::string>();
    }
    selection.positions = std::move(chosen.positions);
    selection.sets = std::move(chosen.sets);
    selection.cloud = !selection.sets.empty()
      ? mlsvtk::pointCloud(selection.positions, { { mlsvtk::fields::ConstraintSet, &selection.sets } })
      : mlsvtk::pointCloud(selection.positions, {});
    // the centroid of the selected positions of all processes, each position once
    const mlsdeform::PointList all = mlsdeform::gatherPositions(selection.positions, {}, group).positions;
    selection.selectedAnywhere = !all.empty();
    selection.centroid.setZero();
    for (const auto& x : all)
    {
      selection.centroid += x / static_cast<double>(all.size());
    }
    selection.inputs = std::move(inputs);
    selection.valid = true;
    ++this->NumberOfSelections;
  }
}

void vtkConstraintRegion::WriteOutput(vtkPolyData* output, int role, const Inputs& in, const mlsdeform::Collective& group)
{
  Selection& selection = *this->Selected;
  DesignVariableList& designs = *this->Designs;
  const bool controlled = !designs.controls.empty(); // then only the control points are held
  if (controlled && (designs.heldSelection != this->NumberOfSelections || !(designs.heldControls == designs.controls)))
  {
    designs.held = mlsvtk::holdControlPoints(designs.controls, selection.positions, in.sets, group);
    designs.heldCloud = mlsvtk::pointCloud(designs.held.positions, {});
    designs.heldControls = designs.controls;
    designs.heldSelection = this->NumberOfSelections;
  }
  const mlsdeform::PointList& selected = controlled ? designs.held.positions : selection.positions;
  // Prescribed displacement of a handle: scale, rotate, translate about the pivot.
  const mlsdeform::Vec3 pivot = this->UseCentroid && selection.selectedAnywhere ? selection.centroid : mlsdeform::Vec3(this->Center);
  std::copy(pivot.data(), pivot.data() + 3, this->Pivot);
  mlsvtk::HandleMotion motion;
  std::copy(this->Translation, this->Translation + 3, motion.translation);
  std::copy(this->Rotation, this->Rotation + 3, motion.rotation);
  std::copy(this->Scale, this->Scale + 3, motion.scale);
  const std::vector<mlsvtk::DesignVariable>& variables = this->Designs->variables;
  const mlsvtk::DesignedMotion map(motion, pivot, variables);

  output->ShallowCopy(controlled ? designs.heldCloud : selection.cloud);
  if (!selection.displacement || selection.displacement->GetReferenceCount() > 1)
  {
    selection.displacement = vtkSmartPointer<vtkDoubleArray>::New(); // the last one is still in use downstream
  }
  vtkDoubleArray* displacement = selection.displacement;
  displacement->SetName(mlsvtk::fields::PrescribedDisplacement);
  displacement->SetNumberOfComponents(3);
  displacement->SetNumberOfTuples(static_cast<vtkIdType>(selected.size()));
  double* d = displacement->GetPointer(0);
  vtkNew<vtkDoubleArray> derivatives; // d(dbar)/dp, 3 per design variable
  derivatives->SetName(mlsvtk::fields::PrescribedDerivatives);
  derivatives->SetNumberOfComponents(3 * static_cast<int>(std::max<std::size_t>(1, variables.size())));
  derivatives->SetNumberOfTuples(variables.empty() ? 0 : static_cast<vtkIdType>(selected.size()));
  const bool moves = role == Handle;
  // the Local variables' columns: x' = x + motion(x) + p_v a at a control point of v (ControlPoints.h)
  std::vector<int> column(designs.controls.size());
  for (std::size_t c = 0; c < designs.controls.size(); ++c)
  {
    column[c] = static_cast<int>(std::find_if(variables.begin(), variables.end(),
      [&](const mlsvtk::DesignVariable& v) { return v.name == designs.controls[c].variable; }) - variables.begin());
  }
  vtkNew<vtkDoubleArray> directions;
  directions->SetName(mlsvtk::fields::ControlDirection);
  directions->SetNumberOfComponents(3);
  for (std::size_t i = 0; i < selected.size(); ++i)
  {
    double* derivative = variables.empty() ? nullptr : derivatives->GetPointer(3 * variables.size() * i);
    if (moves)
    {
      map.displace(selected[i], d + 3 * i, derivative);
    }
    else
    {
      std::fill_n(d + 3 * i, 3, 0.0);
    }
    if (controlled)
    {
      const int c = designs.held.control[i];
      const mlsdeform::Vec3& a = designs.held.directions[c];
      for (int k = 0; k < 3; ++k)
      {
        d[3 * i + k] += variables[column[c]].value * a[k];
        derivative[3 * column[c] + k] = a[k];
      }
      directions->InsertNextTuple(a.data());
    }
  }
  displacement->Modified();
  output->GetPointData()->AddArray(displacement);
  if (controlled)
  {
    output->GetPointData()->AddArray(directions);
  }

  vtkNew<vtkIntArray> roleArray;
  roleArray->SetName(mlsvtk::fields::Role);
  roleArray->InsertNextValue(role);
  vtkNew<vtkStringArray> roleName;
  roleName->SetName(mlsvtk::fields::RoleName);
  roleName->InsertNextValue(GetRoleName(role));
  vtkNew<vtkDoubleArray> weight;
  weight->SetName(mlsvtk::fields::Weight);
  weight->InsertNextValue(this->Weight);
  output->GetFieldData()->AddArray(roleArray);
  output->GetFieldData()->AddArray(roleName);
  output->GetFieldData()->AddArray(weight);
  vtkNew<vtkIntArray> dragging;
  dragging->SetName(mlsvtk::fields::Dragging);
  dragging->InsertNextValue(this->Dragging ? 1 : 0);
  output->GetFieldData()->AddArray(dragging);
  if (role == Symmetric)
  {
    vtkNew<vtkDoubleArray> mirror;
    mirror->SetName(mlsvtk::fields::SymmetryPlane);
    mirror->SetNumberOfComponents(6);
    const double plane[6] = { this->SymmetryOrigin[0], this->SymmetryOrigin[1], this->SymmetryOrigin[2], this->SymmetryNormal[0],
      this->SymmetryNormal[1], this->SymmetryNormal[2] };
    mirror->InsertNextTuple(plane);
    output->GetFieldData()->AddArray(mirror);
  }
  if (role == Coplanar || role == Distance)
  {
    vtkNew<vtkIntArray> group;
    group->SetName(mlsvtk::fields::ConstraintGroup);
    group->InsertNextValue(this->ConstraintGroup);
    output->GetFieldData()->AddArray(group);
  }
  if (role == Distance)
  {
    vtkNew<vtkDoubleArray> axis;
    axis->SetName(mlsvtk::fields::DistanceAxis);
    axis->SetNumberOfComponents(3);
    axis->InsertNextTuple(this->DistanceAxis);
    output->GetFieldData()->AddArray(axis);
  }
  if (role == Offset)
  {
    vtkNew<vtkDoubleArray> bound;
    bound->SetName(mlsvtk::fields::MinimumDistance);
    bound->InsertNextValue(this->MinimumDistance);
    output->GetFieldData()->AddArray(bound);
    output->GetFieldData()->AddArray(mlsvtk::triangleCorners(in.surfaceSets, mlsvtk::fields::ReferenceTriangles));
  }
  if (!variables.empty())
  {
    output->GetPointData()->AddArray(derivatives);
    vtkNew<vtkStringArray> names;
    names->SetName(mlsvtk::fields::DesignVariableNames);
    vtkNew<vtkDoubleArray> values, bounds;
    values->SetName(mlsvtk::fields::DesignVariableValues);
    bounds->SetName(mlsvtk::fields::DesignVariableBounds);
    bounds->SetNumberOfComponents(2);
    for (const mlsvtk::DesignVariable& v : variables)
    {
      names->InsertNextValue(v.name);
      values->InsertNextValue(v.value);
      bounds->InsertNextTuple2(v.lower, v.upper);
    }
    output->GetFieldData()->AddArray(names);
    output->GetFieldData()->AddArray(values);
    output->GetFieldData()->AddArray(bounds);
  }
}

void vtkConstraintRegion::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Role: " << GetRoleName(this->Role) << "\n"
     << indent << "SelectionMode: " << this->SelectionMode << "\n"
     << indent << "Region: " << this->Region << "\n"
     << indent << "InsideOut: " << this->InsideOut << "\n"
     << indent << "Range: " << this->Range[0] << " " << this->Range[1] << "\n"
     << indent << "PrimitiveId: " << this->PrimitiveId << "\n"
     << indent << "NumberOfLayers: " << this->NumberOfLayers << "\n"
     << indent << "CellSets: " << this->CellSets << "\n"
     << indent << "Blocks: " << this->BlockNames.size() << "\n"
     << indent << "Sets: " << this->SetNames.size() << "\n"
     << indent << "Translation: " << this->Translation[0] << " " << this->Translation[1] << " " << this->Translation[2] << "\n"
     << indent << "Rotation: " << this->Rotation[0] << " " << this->Rotation[1] << " " << this->Rotation[2] << "\n"
     << indent << "Scale: " << this->Scale[0] << " " << this->Scale[1] << " " << this->Scale[2] << "\n"
     << indent << "Center: " << this->Center[0] << " " << this->Center[1] << " " << this->Center[2] << "\n"
     << indent << "UseCentroid: " << this->UseCentroid << "\n"
     << indent << "Weight: " << this->Weight << "\n"
     << indent << "Dragging: " << this->Dragging << "\n"
     << indent << "DesignVariables: " << this->Designs->variables.size() << "\n"
     << indent << "ControlPoints: " << this->Designs->controls.size() << "\n";
}
