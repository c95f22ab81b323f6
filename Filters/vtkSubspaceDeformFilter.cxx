#include "vtkSubspaceDeformFilter.h"

#include "SpaceDeformation.h"

#include "MLSGeometry.h"
#include "SubspaceOperators.h"
#include "vtkConstraintRegion.h"

#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMultiProcessController.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <chrono>
#include <memory>
#include <sstream>

using namespace mlsdeform;

namespace
{
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Region
{
  int role = 0;
  double weight = 1;
  PointList positions;
  PointDisplacements prescribed;
};

// The Regions inputs: handle and fixed regions, and geometric constraints (section 6).
struct RegionInputs
{
  std::vector<Region> dirichlet;
  std::vector<ShapeConstraint> constraints;
};

RegionInputs readRegions(vtkInformationVector* connections)
{
  RegionInputs inputs;
  std::vector<Region>& regions = inputs.dirichlet;
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
    Region region;
    region.role = role->GetValue(0);
    if (vtkDataArray* weight = data->GetFieldData()->GetArray("Weight"))
    {
      region.weight = weight->GetTuple1(0);
    }
    const vtkIdType n = data->GetNumberOfPoints();
    if (n == 0)
    {
      throw InvalidInputException(which + " (" + vtkConstraintRegion::GetRoleName(region.role) + ") selects no point");
    }
    region.positions = mlsgeometry::points({ data });
    requireFinite(region.positions, (which + " positions").c_str());
    if (region.role >= vtkConstraintRegion::Planarity && region.role <= vtkConstraintRegion::Rigid)
    {
      // the roles Planarity ... Rigid follow the order of ConstraintType
      inputs.constraints.push_back(
        { static_cast<ConstraintType>(region.role - vtkConstraintRegion::Planarity), std::move(region.positions), region.weight });
      continue;
    }
    region.prescribed.resize(n, 3);
    if (auto* values = vtkDoubleArray::SafeDownCast(displacement))
    {
      region.prescribed = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(values->GetPointer(0), n, 3);
    }
    else
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        for (int d = 0; d < 3; ++d)
        {
          region.prescribed(i, d) = displacement->GetComponent(i, d);
        }
      }
    }
    if (!region.prescribed.allFinite())
    {
      throw InvalidInputException(which + ": prescribed displacements are not finite");
    }
    regions.push_back(std::move(region));
  }
  bool handle = false;
  for (const Region& r : regions)
  {
    handle = handle || r.role == vtkConstraintRegion::Handle;
  }
  if (!handle)
  {
    throw InvalidInputException("no Handle region among the Regions inputs: nothing would move");
  }
  return inputs;
}

bool sameConstraints(const std::vector<ShapeConstraint>& a, const std::vector<ShapeConstraint>& b)
{
  bool same = a.size() == b.size();
  for (std::size_t t = 0; same && t < a.size(); ++t)
  {
    same = a[t].type == b[t].type && a[t].weight == b[t].weight && a[t].positions == b[t].positions;
  }
  return same;
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

// Field data with one tuple per constraint region: type, points, residual (largest distance to
// the projection, relative to the bounding-box diagonal), iterations, converged. Returns the
// largest relative residual.
double reportConstraints(
  vtkFieldData* field, const std::vector<ShapeConstraint>& constraints, const SpaceDeformation::Solution& solution, const PointList& points)
{
  if (constraints.empty())
  {
    return 0;
  }
  const double diagonal = boundingBox(points).size().norm();
  vtkNew<vtkStringArray> type;
  type->SetName("ConstraintType");
  vtkNew<vtkIntArray> count, iterations, converged;
  count->SetName("ConstraintPoints");
  iterations->SetName("ConstraintIterations");
  converged->SetName("ConstraintConverged");
  vtkNew<vtkDoubleArray> residual;
  residual->SetName("ConstraintResidual");
  for (std::size_t t = 0; t < constraints.size(); ++t)
  {
    type->InsertNextValue(constraintName(constraints[t].type));
    count->InsertNextValue(static_cast<int>(constraints[t].positions.size()));
    residual->InsertNextValue(solution.constraintResidual[t] / diagonal);
    iterations->InsertNextValue(solution.iterations);
    converged->InsertNextValue(solution.converged ? 1 : 0);
  }
  for (vtkAbstractArray* array : std::initializer_list<vtkAbstractArray*>{ type, count, residual, iterations, converged })
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

struct vtkSubspaceDeformFilter::Cache
{
  std::string subspaceKey;
  std::unique_ptr<SpaceDeformation> model;
  std::string geometryKey;          // signature of the points below; empty when Phi is not valid
  PointList points;                 // the input points, concatenated
  SparseRowMatrix geometrySubspace; // Phi at the input points
  std::vector<PointList> regionPositions;
  std::vector<double> regionWeights;
  std::vector<ShapeConstraint> constraints;
  int formulation = 0;
  bool factorized = false;
  EnergyWeights weights;
  double setupTime = 0;

  /// Forgets everything that depends on the samples.
  void reset()
  {
    model.reset();
    geometryKey.clear();
    geometrySubspace = SparseRowMatrix();
    regionPositions.clear();
    regionWeights.clear();
    constraints.clear();
    factorized = false;
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
  int skipped = 0;
  const std::vector<vtkPointSet*> inSets = mlsgeometry::pointSets(input, &skipped);
  const std::vector<vtkPointSet*> outSets = mlsgeometry::pointSets(output);
  if (skipped > 0)
  {
    vtkWarningMacro(<< skipped << " block(s) are not point sets and are passed through unchanged.");
  }
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    if (input->GetNumberOfElements(vtkDataObject::POINT) == 0)
    {
      return 1; // this process holds no piece
    }
    vtkWarningMacro(<< "Running on " << controller->GetNumberOfProcesses()
                    << " processes: each deforms its own piece with its own samples and regions, so pieces may not "
                       "match at their boundaries. Run on one process for a consistent deformation.");
  }
  Cache& cache = *this->Cached;
  bool resampled = false, refactorized = false;
  try
  {
    const auto setupStart = Clock::now();
    const std::string geometryKey = mlsgeometry::pointsSignature(inSets);
    if (geometryKey != cache.geometryKey)
    {
      cache.geometryKey.clear();
      cache.points = mlsgeometry::points(inSets);
      if (cache.points.empty())
      {
        throw InvalidInputException("the input has no points");
      }
      requireFinite(cache.points, "input points");
    }
    const PointList& points = cache.points;
    const RegionInputs inputs = readRegions(inputVector[1]);
    const std::vector<Region>& regions = inputs.dirichlet;

    // 1. The subspace: shape functions and energies.
    const std::string key = this->SubspaceKey(inSets, inputVector);
    if (!cache.model || key != cache.subspaceKey)
    {
      cache.reset();
      cache.model = this->BuildSubspace(inSets, inputVector);
      cache.subspaceKey = key;
      ++this->NumberOfSamplings;
      resampled = true;
    }
    SpaceDeformation& model = *cache.model;

    // 2. Phi at the points to deform.
    if (cache.geometryKey.empty())
    {
      std::vector<int> outside;
      cache.geometrySubspace = subspaceMatrix(model.basis(), points, &outside, { &mlsgeometry::reportProgress, this, 0.6, 0.9 });
      if (!outside.empty())
      {
        throw InvalidInputException(std::to_string(outside.size()) + " input point(s) lie outside every MLS support (e.g. point " +
          std::to_string(outside[0]) + "): the samples do not cover the input; sample this input or raise Cover");
      }
      cache.geometryKey = geometryKey;
    }

    // 3. Regions and the factorization of eq. 14.
    bool sameRegions = regions.size() == cache.regionPositions.size();
    for (std::size_t r = 0; sameRegions && r < regions.size(); ++r)
    {
      sameRegions = regions[r].positions == cache.regionPositions[r] && regions[r].weight == cache.regionWeights[r];
    }
    if (!sameRegions)
    {
      std::vector<DirichletRegion> dirichlet;
      for (const Region& r : regions)
      {
        dirichlet.push_back({ r.positions, r.weight });
      }
      cache.regionPositions.clear();
      cache.factorized = false;
      model.setRegions(dirichlet);
      cache.regionWeights.clear();
      for (const Region& r : regions)
      {
        cache.regionPositions.push_back(r.positions);
        cache.regionWeights.push_back(r.weight);
      }
    }
    if (!sameConstraints(inputs.constraints, cache.constraints) || this->ConstraintFormulation != cache.formulation)
    {
      cache.constraints.clear();
      cache.factorized = false;
      model.setConstraints(inputs.constraints, static_cast<mlsdeform::ConstraintFormulation>(this->ConstraintFormulation));
      cache.constraints = inputs.constraints;
      cache.formulation = this->ConstraintFormulation;
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

    // 4. The variation: right-hand side, back-substitution, d(x) = Phi(x) w.
    const auto solveStart = Clock::now();
    std::vector<PointDisplacementsView> prescribed;
    for (const Region& r : regions)
    {
      prescribed.emplace_back(r.prescribed.data(), r.prescribed.rows(), 3);
    }
    IterationSettings settings;
    settings.maxIterations = this->MaxIterations;
    settings.tolerance = this->Tolerance;
    settings.andersonDepth = this->Acceleration == Anderson ? 5 : 0;
    const SpaceDeformation::Solution solution = model.solve(prescribed, settings);
    const Displacements& w = solution.w;
    ++this->NumberOfSolves;
    long offset = 0;
    for (std::size_t s = 0; s < inSets.size(); ++s)
    {
      const vtkIdType n = inSets[s]->GetNumberOfPoints();
      if (n == 0)
      {
        continue;
      }
      vtkNew<vtkDoubleArray> displacement;
      displacement->SetName("Displacement");
      displacement->SetNumberOfComponents(3);
      displacement->SetNumberOfTuples(n);
      multiplyRows(cache.geometrySubspace, w, offset, offset + n, displacement->GetPointer(0));
      vtkNew<vtkPoints> moved;
      moved->SetDataType(inSets[s]->GetPoints()->GetDataType());
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
      offset += n;
      outSets[s]->SetPoints(moved);
      outSets[s]->GetPointData()->AddArray(displacement);
    }
    const double solveTime = secondsSince(solveStart);

    const std::vector<double>& residuals = solution.rmsResidual;
    double handleResidual = 0, fixedResidual = 0;
    for (std::size_t r = 0; r < regions.size(); ++r)
    {
      double& residual = regions[r].role == vtkConstraintRegion::Handle ? handleResidual : fixedResidual;
      residual = std::max(residual, residuals[r]);
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
    const double constraintResidual = reportConstraints(field, inputs.constraints, solution, points);
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
    copyInput(input, output); // leave the output as the unchanged input
    vtkErrorMacro(<< this->GetClassName() << " failed: " << e.what() << ". The output is the unchanged input.");
    return 0;
  }
  return 1;
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
     << indent << "Acceleration: " << this->Acceleration << "\n";
}
