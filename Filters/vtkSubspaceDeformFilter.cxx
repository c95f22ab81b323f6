#include "vtkSubspaceDeformFilter.h"

#include "Common/BoundingBox.h"
#include "Solver/SpaceDeformation.h"

#include "Session/SubspaceDependencies.h"
#include "Adapters/ArrayRanges.h"
#include "Common/GatheredPositions.h"
#include "Adapters/PointSets.h"
#include "Adapters/Stamp.h"
#include "Adapters/AlgorithmProgress.h"
#include "Adapters/ProcessCollective.h"
#include "Adapters/VolumeMeshQuality.h"
#include "Basis/SubspaceOperators.h"
#include "vtkConstraintRegion.h"

#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <tuple>

using namespace mlsdeform;
using namespace mlsvtk;

namespace
{
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One Regions input as last read (paper sections 3 and 6: handle and fixed regions, geometric
// constraints). Its local positions are read again only when the stamp of its points changes;
// the positions of all processes are gathered again (GatheredPositions.h) when a process's
// changed, and get a new version only when their values do.
struct RegionInput
{
  int role = 0;
  double weight = 1;
  mlsvtk::Stamp stamp;
  PointList localPositions;
  std::vector<int> localSets; // a ConstraintSet per local position (a ConstraintRegion with CellSets), or empty
  bool localChanged = true;   // since the last gathering
  vtkDataArray* displacement = nullptr; // this update's local PrescribedDisplacement

  mlsdeform::GatheredPositions gathered; // the positions of all processes, in canonical order
  long version = -1;                         // of the gathered positions and sets
};

bool isConstraint(int role)
{
  return (role >= vtkConstraintRegion::Planarity && role <= vtkConstraintRegion::Rigid) || role == vtkConstraintRegion::Slip;
}

ConstraintType constraintType(int role)
{
  switch (role)
  {
    case vtkConstraintRegion::Circularity:
      return ConstraintType::Circularity;
    case vtkConstraintRegion::Cylinder:
      return ConstraintType::Cylinder;
    case vtkConstraintRegion::FeatureLine:
      return ConstraintType::FeatureLine;
    case vtkConstraintRegion::Rigid:
      return ConstraintType::Rigid;
    case vtkConstraintRegion::Slip:
      return ConstraintType::Slip;
    default:
      return ConstraintType::Planarity;
  }
}

// The constraint sets of a constraint region: one, or one per ConstraintSet value (a
// ConstraintRegion with CellSets: every cell). A set's weight is its share of the region's
// positions times the region's weight, so that the sets of a region together weigh as the region
// would as one set (every term is a mean square, ShapeConstraints.h).
void addConstraintSets(const RegionInput& region, std::vector<ShapeConstraint>& shapes)
{
  const ConstraintType type = constraintType(region.role);
  if (region.gathered.sets.empty())
  {
    shapes.push_back({ type, region.gathered.positions, region.weight });
    return;
  }
  std::map<int, PointList> sets;
  for (std::size_t i = 0; i < region.gathered.positions.size(); ++i)
  {
    sets[region.gathered.sets[i]].push_back(region.gathered.positions[i]);
  }
  const double share = region.weight / static_cast<double>(region.gathered.positions.size());
  for (auto& [id, positions] : sets)
  {
    const double weight = share * static_cast<double>(positions.size());
    shapes.push_back({ type, std::move(positions), weight });
  }
}

// Reads this process's part of the Regions inputs into regions (one per connection).
void readRegions(vtkInformationVector* connections, std::vector<RegionInput>& regions)
{
  regions.resize(connections->GetNumberOfInformationObjects());
  for (int c = 0; c < connections->GetNumberOfInformationObjects(); ++c)
  {
    vtkPolyData* data = vtkPolyData::GetData(connections, c);
    const std::string which = "Regions input #" + std::to_string(c);
    auto* role = data ? vtkIntArray::SafeDownCast(data->GetFieldData()->GetArray("Role")) : nullptr;
    vtkDataArray* displacement = data ? data->GetPointData()->GetArray("PrescribedDisplacement") : nullptr;
    if (!role || role->GetNumberOfValues() < 1 || !displacement || displacement->GetNumberOfComponents() != 3)
    {
      throw InvalidInputException(which + " is not a ConstraintRegion output (no Role or PrescribedDisplacement)");
    }
    RegionInput& region = regions[c];
    region.role = role->GetValue(0);
    region.displacement = displacement;
    vtkDataArray* weight = data->GetFieldData()->GetArray("Weight");
    region.weight = weight ? weight->GetTuple1(0) : 1.0;
    mlsvtk::Stamp stamp = mlsvtk::pointsStamp({ data });
    if (stamp != region.stamp)
    {
      PointList positions = mlsvtk::points({ data });
      requireFinite(positions, (which + " positions").c_str());
      std::vector<int> sets;
      if (vtkDataArray* setArray = data->GetPointData()->GetArray("ConstraintSet"))
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
  }
}

// Gathers the regions' positions from all processes when one process's changed (versions from
// nextVersion); throws for a region that selects no point anywhere and when no region is a handle.
void gatherRegions(std::vector<RegionInput>& regions, long& nextVersion, const Collective& group)
{
  bool changed = false;
  for (const RegionInput& region : regions)
  {
    changed = changed || region.localChanged;
  }
  if (group.any(changed))
  {
    for (RegionInput& region : regions)
    {
      mlsdeform::GatheredPositions gathered = mlsdeform::gatherPositions(region.localPositions, region.localSets, group);
      if (gathered.positions != region.gathered.positions || gathered.sets != region.gathered.sets || region.version < 0)
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
      throw InvalidInputException("Regions input #" + std::to_string(c) + " (" + vtkConstraintRegion::GetRoleName(regions[c].role) + ") selects no point");
    }
    handle = handle || regions[c].role == vtkConstraintRegion::Handle;
  }
  if (!handle)
  {
    throw InvalidInputException("no Handle region among the Regions inputs: nothing would move");
  }
}

// A Slip region's plane and where its points are: every point of the input that lies on the
// plane within the region's bounds is one of them (a space deformation knows positions only, so
// a patch and the volume mesh that share a point treat it alike).
struct SlipPlane
{
  Plane plane;
  BoundingBox bounds; // the region's box, enlarged by the plane's tolerance
  double tolerance = 0;

  bool holds(const Vec3& x) const
  {
    return (x.array() >= bounds.lower.array()).all() && (x.array() <= bounds.upper.array()).all() &&
      std::abs(plane.normal.dot(x - plane.point)) <= tolerance;
  }
};

// The Slip regions' planes; throws InvalidInputException for a region that is not planar (its
// points farther than 1e-6 of its diagonal from their plane: round-off of float coordinates
// is 1e-7).
std::vector<SlipPlane> slipPlanes(const std::vector<RegionInput>& regions)
{
  std::vector<SlipPlane> planes;
  for (std::size_t c = 0; c < regions.size(); ++c)
  {
    if (regions[c].role != vtkConstraintRegion::Slip)
    {
      continue;
    }
    SlipPlane slip;
    slip.bounds = boundingBox(regions[c].gathered.positions);
    const double diagonal = slip.bounds.size().norm();
    slip.plane = fitPlane(regions[c].gathered.positions);
    if (regions[c].gathered.positions.size() < 3 || slip.plane.farthest > 1e-6 * diagonal)
    {
      throw InvalidInputException("Regions input #" + std::to_string(c) + " (Slip) is not a plane: its points lie up to " +
        std::to_string(slip.plane.farthest / diagonal) + " of their diagonal from their least-squares plane (at most 1e-6)");
    }
    slip.tolerance = slip.plane.farthest + 1e-9 * diagonal;
    slip.bounds.lower.array() -= slip.tolerance;
    slip.bounds.upper.array() += slip.tolerance;
    planes.push_back(slip);
  }
  return planes;
}

// The displacement of every point on a slip plane loses its normal component: the iteration
// leaves them within its tolerance of the plane, this puts them on it (as OpenFOAM's slip does).
void slideOnPlanes(const std::vector<SlipPlane>& planes, const PointList& points, long offset, vtkIdType n, double* d)
{
  if (planes.empty())
  {
    return;
  }
#pragma omp parallel for schedule(static)
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (const SlipPlane& slip : planes)
    {
      if (slip.holds(points[offset + i]))
      {
        Eigen::Map<Vec3> displacement(d + 3 * i);
        displacement -= slip.plane.normal.dot(displacement) * slip.plane.normal;
      }
    }
  }
}

// The output starts as the unchanged input: shallow copies in new leaf objects, so that setting
// new points on them never touches the input.
void copyInput(vtkDataObject* input, vtkDataObject* output)
{
  auto* inComposite = vtkCompositeDataSet::SafeDownCast(input);
  auto* outComposite = vtkCompositeDataSet::SafeDownCast(output);
  if (inComposite && outComposite)
  {
    outComposite->CopyStructure(inComposite);
    vtkSmartPointer<vtkCompositeDataIterator> it = vtkSmartPointer<vtkCompositeDataIterator>::Take(inComposite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      vtkDataObject* leaf = it->GetCurrentDataObject();
      vtkSmartPointer<vtkDataObject> copy = vtkSmartPointer<vtkDataObject>::Take(leaf->NewInstance());
      copy->ShallowCopy(leaf);
      outComposite->SetDataSet(it, copy);
    }
    outComposite->GetFieldData()->ShallowCopy(inComposite->GetFieldData());
  }
  else
  {
    output->ShallowCopy(input);
  }
}

// x + d written straight into a float or double points array (false for other types).
template <typename Array>
bool writeMoved(vtkDataArray* data, const PointList& points, long offset, const double* d, vtkIdType n)
{
  auto* array = Array::SafeDownCast(data);
  if (!array)
  {
    return false;
  }
  auto* out = array->GetPointer(0);
#pragma omp parallel for schedule(static)
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      out[3 * i + c] = static_cast<typename Array::ValueType>(points[offset + i][c] + d[3 * i + c]);
    }
  }
  return true;
}

// An output array of the previous update, to be written again, when it fits and no one but the
// cache holds it (the output released it when it was reset to the input); else a new one.
template <typename Object>
Object* reusable(vtkSmartPointer<Object>& kept, bool fits)
{
  if (!kept || !fits || kept->GetReferenceCount() > 1)
  {
    kept = vtkSmartPointer<Object>::New();
  }
  return kept;
}

// Field data with one tuple per constraint region: type, points, sets, residual (largest distance
// to the projection over its sets, relative to the bounding-box diagonal), iterations, converged.
// Returns the largest relative residual.
double reportConstraints(vtkFieldData* field, const std::vector<RegionInput>& regions, const SpaceDeformation::Solution& solution, double diagonal)
{
  std::vector<const RegionInput*> constraints;
  for (const RegionInput& r : regions)
  {
    if (isConstraint(r.role))
    {
      constraints.push_back(&r);
    }
  }
  if (constraints.empty())
  {
    return 0;
  }
  vtkNew<vtkStringArray> type;
  type->SetName("ConstraintType");
  vtkNew<vtkIntArray> count, setCount, iterations, converged;
  count->SetName("ConstraintPoints");
  setCount->SetName("ConstraintSets");
  iterations->SetName("ConstraintIterations");
  converged->SetName("ConstraintConverged");
  vtkNew<vtkDoubleArray> residual;
  residual->SetName("ConstraintResidual");
  std::size_t set = 0; // a region's sets are consecutive (addConstraintSets)
  for (const RegionInput* r : constraints)
  {
    type->InsertNextValue(constraintName(constraintType(r->role)));
    count->InsertNextValue(static_cast<int>(r->gathered.positions.size()));
    setCount->InsertNextValue(r->gathered.setCount);
    const auto begin = solution.constraintResidual.begin() + static_cast<long>(set);
    residual->InsertNextValue(*std::max_element(begin, begin + r->gathered.setCount) / diagonal);
    set += static_cast<std::size_t>(r->gathered.setCount);
    iterations->InsertNextValue(solution.iterations);
    converged->InsertNextValue(solution.converged ? 1 : 0);
  }
  for (vtkAbstractArray* array : std::initializer_list<vtkAbstractArray*>{ type, count, setCount, residual, iterations, converged })
  {
    field->AddArray(array);
  }
  return residual->GetRange()[1];
}

void addField(vtkFieldData* field, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  field->AddArray(array);
}
}

// What was read from the inputs, what the set-up was built from, and the output arrays. Values
// get versions when they change; each step of the set-up records the versions and exact values
// it was built from and is redone when they differ (-1: not built).
struct vtkSubspaceDeformFilter::Cache
{
  long nextVersion = 0;
  mlsvtk::Stamp pointsStamp; // of the input points below
  PointList points;               // the input points, concatenated
  long pointsVersion = -1;
  std::vector<RegionInput> regions;
  std::vector<std::pair<long, int>> slipKey; // (version, role) per region the slip planes were fitted to
  std::vector<SlipPlane> slips;

  // 1. the subspace
  std::unique_ptr<SpaceDeformation> model;
  mlsvtk::SubspaceDependencies dependencies;
  mlsvtk::Stamp cellsStamp;
  long modelPoints = -1;
  // 2. Phi at the input points
  RowBlocks geometrySubspace;
  long phiPoints = -1;
  // 3. the regions, 4. the constraints: (version, weight) and (version, type, weight) per region
  std::vector<std::pair<long, double>> dirichlet;
  std::vector<std::tuple<long, int, double>> constraints;
  int formulation = -1;
  bool regionsSet = false, constraintsSet = false;
  // 5. the factorization
  bool factorized = false;
  EnergyWeights weights;
  double setupTime = 0;

  // the output arrays per point set, written again by the next update when no one else holds them
  std::vector<vtkSmartPointer<vtkPoints>> moved;
  std::vector<vtkSmartPointer<vtkDoubleArray>> displacement;
  std::vector<std::vector<double>> prescribed; // the regions' PrescribedDisplacement of all processes, gathered
  double diagonal = -1;                         // of the bounding box of all processes' points (-1: not known)

  // the volume mesh's faces and its quality before deformation, per point set (MeshQuality)
  mlsvtk::Stamp qualityStamp; // of the cells and points they were measured on
  std::vector<std::unique_ptr<mlsvtk::VolumeMeshQuality>> quality;
  mlsvtk::QualitySummary originalQuality;

  /// Forgets everything built on the subspace.
  void resetModel()
  {
    model.reset();
    modelPoints = phiPoints = -1;
    geometrySubspace = RowBlocks();
    regionsSet = constraintsSet = factorized = false;
  }
};

vtkSubspaceDeformFilter::vtkSubspaceDeformFilter(int numberOfInputPorts)
  : Cached(new Cache)
{
  this->SetNumberOfInputPorts(numberOfInputPorts);
}

vtkSubspaceDeformFilter::~vtkSubspaceDeformFilter()
{
  delete this->Cached;
}

int vtkSubspaceDeformFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  return 1;
}

int vtkSubspaceDeformFilter::RequestData(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  copyInput(input, output);
  this->SetErrorCode(vtkErrorCode::NoError);
  int skipped = 0;
  const std::vector<vtkPointSet*> inSets = mlsvtk::pointSets(input, &skipped);
  const std::vector<vtkPointSet*> outSets = mlsvtk::pointSets(output);
  if (skipped > 0)
  {
    vtkWarningMacro(<< skipped << " block(s) are not point sets and are passed through unchanged.");
  }
  // Split over processes, every process holds the same samples, regions and factorization and
  // deforms its own points; what one process finds wrong stops all of them at the same step.
  const mlsvtk::ProcessCollective group;
  Cache& cache = *this->Cached;
  bool resampled = false, refactorized = false;
  try
  {
    const auto setupStart = Clock::now();
    agree(group, [&] {
      // The input points: read again when their stamp changes, a new version when their values do.
      mlsvtk::Stamp pointsStamp = mlsvtk::pointsStamp(inSets);
      if (pointsStamp != cache.pointsStamp)
      {
        PointList points = mlsvtk::points(inSets);
        requireFinite(points, "input points");
        if (points != cache.points || cache.pointsVersion < 0)
        {
          cache.points = std::move(points);
          cache.pointsVersion = cache.nextVersion++;
          cache.diagonal = -1;
        }
        cache.pointsStamp = std::move(pointsStamp);
      }
      readRegions(inputVector[1], cache.regions);
    });
    const PointList& points = cache.points;
    if (!group.any(!points.empty()))
    {
      throw InvalidInputException("the input has no points");
    }
    if (group.any(cache.diagonal < 0))
    {
      cache.diagonal = boundingBox(points, group).size().norm();
    }
    gatherRegions(cache.regions, cache.nextVersion, group);
    // the slip planes: fitted again only when a region's positions or role change
    std::vector<std::pair<long, int>> regionKey;
    for (const RegionInput& r : cache.regions)
    {
      regionKey.emplace_back(r.version, r.role);
    }
    if (regionKey != cache.slipKey)
    {
      cache.slipKey.clear();
      cache.slips = slipPlanes(cache.regions);
      cache.slipKey = std::move(regionKey);
    }
    const std::vector<SlipPlane>& slips = cache.slips;

    // 1. The subspace: shape functions and energies.
    mlsvtk::SubspaceDependencies dependencies = this->GetSubspaceDependencies(inputVector);
    mlsvtk::Stamp cellsStamp = dependencies.geometry ? mlsvtk::cellsStamp(inSets) : mlsvtk::Stamp();
    const long modelPoints = dependencies.geometry ? cache.pointsVersion : 0;
    if (group.any(!cache.model || !(dependencies == cache.dependencies) || cellsStamp != cache.cellsStamp || modelPoints != cache.modelPoints))
    {
      cache.resetModel();
      cache.model = this->BuildSubspace(inSets, inputVector);
      cache.dependencies = std::move(dependencies);
      cache.cellsStamp = std::move(cellsStamp);
      cache.modelPoints = modelPoints;
      ++this->NumberOfSamplings;
      resampled = true;
    }
    SpaceDeformation& model = *cache.model;

    // 2. Phi at the points to deform.
    agree(group, [&] {
      if (cache.phiPoints != cache.pointsVersion)
      {
        std::vector<int> outside;
        cache.geometrySubspace = subspaceBlocks(model.basis(), points, &outside, { &mlsvtk::reportProgress, this, 0.6, 0.9 });
        if (!outside.empty())
        {
          throw InvalidInputException(std::to_string(outside.size()) + " input point(s) lie outside every MLS support (e.g. point " +
            std::to_string(outside[0]) + "): the samples do not cover the input; sample this input or raise Cover");
        }
        cache.phiPoints = cache.pointsVersion;
      }
    });

    // 3. Regions, 4. constraints and 5. the factorization of eq. 14 (17).
    std::vector<std::pair<long, double>> dirichlet;
    std::vector<std::tuple<long, int, double>> constraints;
    for (const RegionInput& r : cache.regions)
    {
      if (isConstraint(r.role))
      {
        constraints.emplace_back(r.version, r.role, r.weight);
      }
      else
      {
        dirichlet.emplace_back(r.version, r.weight);
      }
    }
    if (!cache.regionsSet || dirichlet != cache.dirichlet)
    {
      std::vector<DirichletRegion> regions;
      PointList positions;
      for (const RegionInput& r : cache.regions)
      {
        if (!isConstraint(r.role))
        {
          regions.push_back({ r.gathered.positions, r.weight });
          positions.insert(positions.end(), r.gathered.positions.begin(), r.gathered.positions.end());
        }
      }
      cache.regionsSet = cache.factorized = false;
      // a region's points are usually input points too (a patch of the mesh): their rows of Phi
      // are copied from step 2's rather than evaluated again
      model.setRegions(regions, { &cache.geometrySubspace, positionsAmong(points, positions) });
      cache.dirichlet = std::move(dirichlet);
      cache.regionsSet = true;
    }
    if (!cache.constraintsSet || constraints != cache.constraints || this->ConstraintFormulation != cache.formulation)
    {
      std::vector<ShapeConstraint> shapes;
      for (const RegionInput& r : cache.regions)
      {
        if (isConstraint(r.role))
        {
          addConstraintSets(r, shapes);
        }
      }
      cache.constraintsSet = cache.factorized = false;
      model.setConstraints(shapes, static_cast<mlsdeform::ConstraintFormulation>(this->ConstraintFormulation));
      cache.constraints = std::move(constraints);
      cache.formulation = this->ConstraintFormulation;
      cache.constraintsSet = true;
    }
    const EnergyWeights weights{ this->StretchWeight, this->BendWeight, this->FixWeight, this->ConstraintWeight };
    if (!cache.factorized || weights.stretch != cache.weights.stretch || weights.bend != cache.weights.bend ||
      weights.fix != cache.weights.fix || weights.constraint != cache.weights.constraint)
    {
      cache.factorized = false;
      model.factorize(weights);
      cache.weights = weights;
      cache.factorized = true;
      ++this->NumberOfFactorizations;
      refactorized = true;
    }
    if (resampled || refactorized)
    {
      cache.setupTime = secondsSince(setupStart);
    }

    // 6. The variation: right-hand side (the PrescribedDisplacement arrays viewed in place),
    // back-substitution, d(x) = Phi(x) w written into the output arrays.
    const auto solveStart = Clock::now();
    std::vector<PointDisplacementsView> prescribed;
    cache.prescribed.resize(cache.regions.size());
    for (std::size_t r = 0; r < cache.regions.size(); ++r)
    {
      vtkDataArray* d = cache.regions[r].displacement;
      if (isConstraint(cache.regions[r].role))
      {
        continue;
      }
      // this process's values, as doubles, then every process's in the regions' gathered order
      const vtkIdType n = d->GetNumberOfTuples();
      std::vector<double> local;
      const double* values = nullptr;
      if (auto* doubles = vtkDoubleArray::SafeDownCast(d))
      {
        values = doubles->GetPointer(0);
      }
      else
      {
        local.resize(3 * static_cast<std::size_t>(n));
        for (vtkIdType i = 0; i < n; ++i)
        {
          d->GetTuple(i, &local[3 * i]);
        }
        values = local.data();
      }
      cache.prescribed[r] = mlsdeform::gatherValues(values, n, 3, cache.regions[r].gathered, group);
      prescribed.emplace_back(cache.prescribed[r].data(), static_cast<long>(cache.regions[r].gathered.positions.size()), 3);
    }
    IterationSettings settings;
    settings.maxIterations = this->MaxIterations;
    settings.tolerance = this->Tolerance;
    settings.andersonDepth = this->Acceleration == Anderson ? 5 : 0;
    const SpaceDeformation::Solution solution = model.solve(prescribed, settings);
    const PointDisplacements w = solution.w; // row-major: a shape function's x, y, z share a cache line
    ++this->NumberOfSolves;
    cache.moved.resize(inSets.size());
    cache.displacement.resize(inSets.size());
    long offset = 0;
    for (std::size_t s = 0; s < inSets.size(); ++s)
    {
      const vtkIdType n = inSets[s]->GetNumberOfPoints();
      if (n == 0)
      {
        continue;
      }
      const int type = inSets[s]->GetPoints()->GetDataType();
      vtkDoubleArray* displacement = reusable(cache.displacement[s], cache.displacement[s] && cache.displacement[s]->GetNumberOfTuples() == n);
      displacement->SetName("Displacement");
      displacement->SetNumberOfComponents(3);
      displacement->SetNumberOfTuples(n);
      multiplyRows(cache.geometrySubspace, w, offset, offset + n, displacement->GetPointer(0));
      slideOnPlanes(slips, points, offset, n, displacement->GetPointer(0));
      displacement->Modified();
      vtkPoints* moved = reusable(cache.moved[s], cache.moved[s] && cache.moved[s]->GetNumberOfPoints() == n && cache.moved[s]->GetDataType() == type);
      moved->SetDataType(type);
      moved->SetNumberOfPoints(n);
      if (!writeMoved<vtkFloatArray>(moved->GetData(), points, offset, displacement->GetPointer(0), n) &&
        !writeMoved<vtkDoubleArray>(moved->GetData(), points, offset, displacement->GetPointer(0), n))
      {
        for (vtkIdType i = 0; i < n; ++i)
        {
          const Vec3 x = points[offset + i] + Vec3(displacement->GetPointer(3 * i));
          moved->SetPoint(i, x.data());
        }
      }
      moved->Modified();
      storeRanges(displacement);
      storeRanges(moved->GetData());
      offset += n;
      outSets[s]->SetPoints(moved);
      outSets[s]->GetPointData()->AddArray(displacement);
    }
    const double solveTime = secondsSince(solveStart);

    const std::vector<double>& residuals = solution.rmsResidual;
    double handleResidual = 0, fixedResidual = 0;
    std::size_t d = 0;
    for (const RegionInput& r : cache.regions)
    {
      if (isConstraint(r.role))
      {
        continue;
      }
      double& residual = r.role == vtkConstraintRegion::Handle ? handleResidual : fixedResidual;
      residual = std::max(residual, residuals[d++]);
    }
    vtkFieldData* field = output->GetFieldData();
    addField(field, "NumberOfSamples", static_cast<double>(model.basis().size()));
    addField(field, "NumberOfIntegrationPoints", static_cast<double>(model.numberOfIntegrationPoints()));
    addField(field, "SetupTime", cache.setupTime);
    addField(field, "SolveTime", solveTime);
    addField(field, "HandleResidual", handleResidual);
    addField(field, "FixedResidual", fixedResidual);
    addField(field, "ReciprocalCondition", model.reciprocalCondition());
    addField(field, "Resampled", resampled ? 1 : 0);
    addField(field, "Refactorized", refactorized ? 1 : 0);
    const double constraintResidual = reportConstraints(field, cache.regions, solution, cache.diagonal);
    if (this->MeshQuality)
    {
      this->ReportMeshQuality(inSets, outSets, field, group);
    }
    if (!solution.converged)
    {
      vtkWarningMacro(<< "The constraints did not converge in MaxIterations = " << this->MaxIterations
                      << " iterations (largest residual " << constraintResidual
                      << " of the bounding-box diagonal): they may conflict with each other or with the targets. "
                         "The output is the last iterate.");
    }
  }
  catch (const std::exception& e)
  {
    // The output is the unchanged input, marked for scripts; the request succeeds so that the
    // pipeline updates again once the input is fixed (a failed request left ParaView's
    // representation stale after two failures in a row).
    copyInput(input, output);
    vtkNew<vtkStringArray> error;
    error->SetName("DeformationError");
    error->InsertNextValue(e.what());
    output->GetFieldData()->AddArray(error);
    this->SetErrorCode(vtkErrorCode::UserError);
    vtkErrorMacro(<< this->GetClassName() << " failed: " << e.what() << ". The output is the unchanged input.");
  }
  return 1;
}

void vtkSubspaceDeformFilter::ReportMeshQuality(
  const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets, vtkFieldData* field, const Collective& group)
{
  // Faces and the original's measures once per input mesh; the deformed mesh's every update. Split
  // over processes, each measures its own piece (the faces between pieces are not measured) and
  // the summaries are combined exactly: counts added, largest values kept.
  Cache& cache = *this->Cached;
  mlsvtk::Stamp stamp = mlsvtk::cellsStamp(inSets);
  const mlsvtk::Stamp points = mlsvtk::pointsStamp(inSets);
  stamp.objects.insert(stamp.objects.end(), points.objects.begin(), points.objects.end());
  if (group.any(stamp != cache.qualityStamp))
  {
    cache.quality.clear();
    cache.originalQuality = mlsvtk::QualitySummary();
    std::string problem;
    try
    {
      for (vtkPointSet* set : inSets)
      {
        auto* grid = vtkUnstructuredGrid::SafeDownCast(set);
        cache.quality.push_back(grid ? std::make_unique<mlsvtk::VolumeMeshQuality>(grid) : nullptr);
        if (cache.quality.back() && cache.quality.back()->hasCells())
        {
          cache.originalQuality.add(cache.quality.back()->original());
        }
      }
    }
    catch (const std::exception& e)
    {
      problem = e.what();
    }
    problem = group.firstError(problem);
    if (!problem.empty())
    {
      // the deformation stands; this mesh's quality is not reported (said once per mesh)
      cache.quality.clear();
      vtkWarningMacro(<< "The mesh quality is not reported: " << problem
                      << ". (ParaView's OpenFOAM reader with Decompose polyhedra on makes such cells; turn it off to "
                         "measure OpenFOAM's own cells.)");
    }
    cache.quality.resize(inSets.size());
    cache.qualityStamp = std::move(stamp);
  }
  mlsvtk::QualitySummary deformed;
  bool measured = false;
  for (std::size_t s = 0; s < outSets.size(); ++s)
  {
    if (cache.quality[s] && cache.quality[s]->hasCells())
    {
      deformed.add(cache.quality[s]->summary(vtkUnstructuredGrid::SafeDownCast(outSets[s])));
      measured = true;
    }
  }
  if (!group.any(measured))
  {
    return;
  }
  for (auto [prefix, q] : { std::make_pair("", deformed), std::make_pair("Original", cache.originalQuality) })
  {
    std::vector<std::int64_t> inverted{ q.inverted };
    group.sum(inverted);
    std::vector<double> largest{ q.maxNonOrthogonality, q.maxSkewness };
    group.maximum(largest);
    addField(field, (std::string(prefix) + "InvertedCells").c_str(), static_cast<double>(inverted[0]));
    addField(field, (std::string(prefix) + "MaxNonOrthogonality").c_str(), largest[0]);
    addField(field, (std::string(prefix) + "MaxSkewness").c_str(), largest[1]);
  }
}

void vtkSubspaceDeformFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "StretchWeight: " << this->StretchWeight << "\n"
     << indent << "BendWeight: " << this->BendWeight << "\n"
     << indent << "FixWeight: " << this->FixWeight << "\n"
     << indent << "ConstraintWeight: " << this->ConstraintWeight << "\n"
     << indent << "ConstraintFormulation: " << this->ConstraintFormulation << "\n"
     << indent << "MaxIterations: " << this->MaxIterations << "\n"
     << indent << "Tolerance: " << this->Tolerance << "\n"
     << indent << "Acceleration: " << this->Acceleration << "\n"
     << indent << "MeshQuality: " << this->MeshQuality << "\n";
}
