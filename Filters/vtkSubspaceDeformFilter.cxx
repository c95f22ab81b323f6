#include "vtkSubspaceDeformFilter.h"

#include "Adapters/CaseFaces.h"
#include "Adapters/CasePath.h"
#include "Adapters/FailurePolicy.h"
#include "Adapters/MeshVolume.h"
#include "Adapters/PointSets.h"
#include "Adapters/ProcessCollective.h"
#include "Adapters/Stamp.h"
#include "Adapters/ReportArrays.h"
#include "Session/DeformationSession.h"
#include "Session/SolutionReport.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include "Common/BoundingBox.h"
#include "Quality/PolygonSurface.h"
#include "Vocabulary/FieldNames.h"
#include "Vocabulary/RegionRoles.h"
#include <vtkErrorCode.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>

#include <algorithm>
#include <chrono>
#include <cmath>

using namespace mlsdeform;
using namespace mlsvtk;

namespace
{
// Throws InvalidInputException for a value that is not finite.
void requireFiniteValues(const std::vector<double>& values, const std::string& what)
{
  for (double v : values)
  {
    if (!std::isfinite(v))
    {
      throw InvalidInputException(what + " has a value that is not finite (NaN or infinity)");
    }
  }
}

// A gradient dJ/dX given per point (n x 3, finite) as doubles; throws InvalidInputException.
std::vector<double> gradientValues(vtkDataArray* gradient, std::size_t n, const std::string& what)
{
  if (!gradient || gradient->GetNumberOfComponents() != 3 || gradient->GetNumberOfTuples() != static_cast<vtkIdType>(n))
  {
    throw InvalidInputException(what + " needs 3 components per output point (" + std::to_string(n) + " points here), not " +
      (gradient ? std::to_string(gradient->GetNumberOfTuples()) + " x " + std::to_string(gradient->GetNumberOfComponents()) : "none"));
  }
  std::vector<double> g(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    gradient->GetTuple(static_cast<vtkIdType>(i), &g[3 * i]);
  }
  requireFiniteValues(g, what);
  return g;
}

// The input's point array `name` over the point sets (zero on a set without it); throws
// InvalidInputException when no process has it or it is not 3 finite components.
std::vector<double> objectiveGradient(const std::vector<vtkPointSet*>& sets, const char* name, std::size_t n, const Collective& group)
{
  std::vector<double> g(3 * n, 0.0);
  bool found = false;
  agree(group, [&] {
    std::size_t offset = 0;
    for (vtkPointSet* set : sets)
    {
      const std::size_t count = static_cast<std::size_t>(set->GetNumberOfPoints());
      if (vtkDataArray* array = set->GetPointData()->GetArray(name))
      {
        const std::vector<double> values = gradientValues(array, count, std::string("ObjectiveGradientArray '") + name + "'");
        std::copy(values.begin(), values.end(), g.begin() + 3 * offset);
        found = true;
      }
      offset += count;
    }
  });
  if (!group.any(found))
  {
    throw InvalidInputException(std::string("ObjectiveGradientArray '") + name + "' is no point array of the input");
  }
  return g;
}

// out as an n x 3 array (its memory reused when it has that size already), to be written.
double* resized(vtkDoubleArray* out, std::size_t n)
{
  out->SetNumberOfComponents(3);
  out->SetNumberOfTuples(static_cast<vtkIdType>(n));
  out->Modified();
  return out->GetPointer(0);
}

/// The rows of g (n rows of 3) that are not zero: their indices (at[i] for row i; i when at is
/// null) and values.
void writeNonZeroRows(const double* g, const int* at, std::size_t n, vtkIdTypeArray* rows, vtkDoubleArray* values)
{
  const auto nonZero = [&](std::size_t i) { return g[3 * i] != 0 || g[3 * i + 1] != 0 || g[3 * i + 2] != 0; };
  vtkIdType count = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    count += nonZero(i) ? 1 : 0;
  }
  rows->SetNumberOfComponents(1);
  rows->SetNumberOfTuples(count);
  values->SetNumberOfComponents(3);
  values->SetNumberOfTuples(count);
  vtkIdType* r = rows->GetPointer(0);
  double* v = values->GetPointer(0);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (nonZero(i))
    {
      *r++ = at ? at[i] : static_cast<vtkIdType>(i);
      v = std::copy_n(g + 3 * i, 3, v);
    }
  }
  rows->Modified();
  values->Modified();
}

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}
}

vtkSubspaceDeformFilter::vtkSubspaceDeformFilter(int numberOfInputPorts)
  : Session(std::make_unique<DeformationSession>(this))
{
  this->SetNumberOfInputPorts(numberOfInputPorts);
}

vtkSubspaceDeformFilter::~vtkSubspaceDeformFilter()
{
  this->SetObjectiveGradientArray(nullptr);
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
  const mlsvtk::ReportArrays reports(inputVector[0], outputVector); // its field data: reports, not fields
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  copyInput(input, output);
  this->SetErrorCode(vtkErrorCode::NoError);
  int skipped = 0;
  const std::vector<vtkPointSet*> inSets = pointSets(input, &skipped);
  const std::vector<vtkPointSet*> outSets = pointSets(output);
  if (skipped > 0)
  {
    vtkWarningMacro(<< skipped << " block(s) are not point sets and are passed through unchanged.");
  }
  // Split over processes, every process holds the same samples, regions and factorization and
  // deforms its own points; what one process finds wrong stops all of them at the same step.
  const ProcessCollective group;
  DeformationSession& session = *this->Session;
  this->SessionSolved = false;
  try
  {
    SolutionFigures figures;
    const auto setupStart = Clock::now();
    if (this->MeshQuality)
    {
      session.readQualityAhead(inSets, mlsvtk::casePathOf(input)); // while the set-up runs
    }
    session.readInputs(inSets, inputVector[1], this->ExtrusionAxis, group);
    figures.resampled = session.updateSubspace(this->GetSubspaceDependencies(inputVector), inSets,
      [&] { return this->BuildSubspace(inSets, inputVector); }, group);
    session.updatePointRows(group);
    session.updateTargets();
    session.updateConstraints(static_cast<mlsdeform::ConstraintFormulation>(this->ConstraintFormulation));
    session.updateExactTargets(this->ExactTargets ? this->TargetBlendRadius : 0.0, this->ExactConstraints, group);
    figures.refactorized =
      session.updateFactorization({ this->StretchWeight, this->BendWeight, this->FixWeight, this->ConstraintWeight });
    if (figures.resampled || figures.refactorized)
    {
      session.setSetupTime(secondsSince(setupStart));
    }

    const auto solveStart = Clock::now();
    IterationSettings settings;
    settings.maxIterations = this->MaxIterations;
    settings.tolerance = this->Tolerance;
    settings.andersonDepth = this->Acceleration == Anderson ? 5 : 0;
    const SpaceDeformation::Solution solution = session.solve(settings, group);
    const std::vector<char> moving = session.movingSets(inSets);
    session.writeOutput(inSets, outSets, moving);
    figures.solveTime = secondsSince(solveStart);
    this->WriteSensitivities(inSets, outSets, moving, output->GetFieldData(), group);
    figures.setupTime = session.setupTime();
    figures.diagonal = session.diagonal();
    figures.targetCorrection = session.targetCorrection();
    figures.targetConflicts = session.targetConflicts();
    figures.constraintConflicts = session.constraintConflicts();

    const double constraintResidual = reportSolution(output->GetFieldData(), session.model(), session.regions(), session.iteratedConstraints(), solution, figures);
    // the volume mesh is measured once it moved (not during a drag's surface-only updates)
    if (this->MeshQuality && !group.any(std::find(moving.begin(), moving.end(), 0) != moving.end()))
    {
      session.reportQuality(inSets, outSets, output->GetFieldData(), mlsvtk::casePathOf(input), mlsvtk::femReaderUpstream(this), group);
    }
    if (!session.targetConflicts().empty())
    {
      vtkWarningMacro(<< "Targets disagree where regions share points: Regions inputs " << session.targetConflicts()
                      << " prescribe different displacements at the same positions; those points meet the mean of their "
                         "targets (HandleResidual and FixedResidual say by how much).");
    }
    if (!session.constraintConflicts().empty())
    {
      vtkWarningMacro(<< "The constraints contradict each other or the targets: Regions inputs " << session.constraintConflicts()
                      << " cannot all hold exactly; the output keeps the targets and is the soft (least-squares) compromise "
                         "of the constraints there (ConstraintResidual says by how much).");
    }
    const auto hasRole = [&](int role) {
      return std::any_of(session.regions().begin(), session.regions().end(), [&](const auto& region) { return region.role == role; });
    };
    if ((figures.resampled || figures.refactorized) && hasRole(mlsvtk::roles::Handle) && !hasRole(mlsvtk::roles::Fixed))
    {
      // nothing holds the model: the least-energy motion is the Handle's motion everywhere
      vtkWarningMacro(<< "No Fixed region: nothing holds the model, so the Handle moves all of it (a rigid motion). Add a Fixed "
                         "region (e.g. a CFD case's inlet and outlet, a deck's supports) to deform it.");
    }
    if (session.model().regularizingStretch() > 0 && (figures.resampled || figures.refactorized))
    {
      vtkWarningMacro(<< "The deformation system was singular with these weights (more MLS samples than the integration points "
                         "determine); it was solved with StretchWeight "
                      << session.model().regularizingStretch()
                      << " instead, which makes the deformation slightly more membrane-like (RegularizingStretchWeight). "
                         "Fewer samples (NumberOfSamples), a larger Cover or IntegrationPointRatio avoid it.");
    }
    if (!solution.converged)
    {
      vtkWarningMacro(<< "The constraints did not converge in MaxIterations = " << this->MaxIterations
                      << " iterations (largest residual " << constraintResidual
                      << " of the bounding-box diagonal): they may conflict with each other or with the targets. "
                         "The output is the last iterate.");
    }
    this->SessionSolved = true;
    this->OutputDeformed = true;
  }
  catch (const AbortedException& e)
  {
    // the previous update's points stay (the executive emptied the output before this request)
    copyInput(input, output);
    const bool kept = this->OutputDeformed && session.restoreOutput(inSets, pointSets(output));
    this->OutputDeformed = kept;
    this->SetErrorCode(vtkErrorCode::UserError);
    return reportFailure(this, outputVector, e,
      kept ? "The output is the previous update's deformed points; what finished is kept, and the next update goes on from there."
           : "The output is the unchanged input; what finished is kept, and the next update goes on from there.");
  }
  catch (const std::exception& e)
  {
    copyInput(input, output);
    this->OutputDeformed = false;
    this->SetErrorCode(vtkErrorCode::UserError);
    return reportFailure(this, outputVector, e, "The output is the unchanged input.");
  }
  return 1;
}

void vtkSubspaceDeformFilter::WriteSensitivities(
  const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets, const std::vector<char>& moving, vtkFieldData* field,
  const Collective& group)
{
  DeformationSession& session = *this->Session;
  if (session.design().size() == 0)
  {
    return;
  }
  writeDesignTable(session.design(), field);
  std::string method = session.model().isLinear() ? "exact: back-substitutions of the factorized system"
                                                  : "implicit differentiation of the constraint iteration's fixed point";
  if (this->ComputeSensitivities)
  {
    session.writeSensitivities(outSets, moving);
  }
  const std::string gradientName = this->ObjectiveGradientArray ? this->ObjectiveGradientArray : "";
  if (!gradientName.empty() && gradientName != "None") // "None": ParaView's choice of no array
  {
    const std::vector<double> gradient = objectiveGradient(inSets, this->ObjectiveGradientArray, session.inputPoints().size(), group);
    vtkNew<vtkDoubleArray> dJdp;
    dJdp->SetName(fields::ObjectiveSensitivity);
    for (double value : session.objectiveSensitivity(gradient, group, method))
    {
      dJdp->InsertNextValue(value);
    }
    field->AddArray(dJdp);
  }
  vtkNew<vtkStringArray> methodName;
  methodName->SetName(fields::SensitivityMethod);
  methodName->InsertNextValue(method);
  field->AddArray(methodName);
}

template <typename Request>
bool vtkSubspaceDeformFilter::RunSensitivityRequest(Request request)
{
  const ProcessCollective group;
  this->SensitivityError.clear();
  try
  {
    agree(group, [&] {
      if (!this->SessionSolved)
      {
        throw InvalidInputException("no successful update to differentiate: update the filter first");
      }
    });
    request(group);
    return true;
  }
  catch (const std::exception& e)
  {
    this->SensitivityError = e.what();
    vtkErrorMacro(<< this->SensitivityError);
    return false;
  }
}

bool vtkSubspaceDeformFilter::GetDeformedPoints(vtkDoubleArray* out)
{
  return this->RunSensitivityRequest([&](const Collective&) {
    if (!out)
    {
      throw InvalidInputException("GetDeformedPoints needs an output array");
    }
    // the points kept for the solution: an optimizer's design measures them next (a mesh volume)
    const PointList& deformed = this->Session->deformedPoints();
    static_assert(sizeof(Vec3) == 3 * sizeof(double), "points as packed doubles");
    std::copy_n(deformed.empty() ? nullptr : deformed.front().data(), 3 * deformed.size(), resized(out, deformed.size()));
  });
}

bool vtkSubspaceDeformFilter::ComputeSensitivityProduct(vtkDoubleArray* seeds, vtkDoubleArray* out)
{
  return this->RunSensitivityRequest([&](const Collective& group) {
    DeformationSession& session = *this->Session;
    std::vector<double> values;
    agree(group, [&] {
      const std::size_t m = session.design().size();
      if (!seeds || !out || seeds->GetNumberOfComponents() != 1 || seeds->GetNumberOfTuples() != static_cast<vtkIdType>(m))
      {
        throw InvalidInputException("ComputeSensitivityProduct needs one seed per design variable (" + std::to_string(m) + ") and an output array");
      }
      for (vtkIdType v = 0; v < seeds->GetNumberOfTuples(); ++v)
      {
        values.push_back(seeds->GetValue(v));
      }
      requireFiniteValues(values, "the seeds");
    });
    const PointField t = session.tangent(values); // may throw: out is resized after it
    const std::size_t n = session.inputPoints().size();
    session.displacement(t, 0, static_cast<long>(n), resized(out, n));
  });
}

bool vtkSubspaceDeformFilter::ComputeObjectiveSensitivity(vtkDataArray* gradient, vtkDoubleArray* out)
{
  return this->RunSensitivityRequest([&](const Collective& group) {
    DeformationSession& session = *this->Session;
    std::vector<double> g;
    agree(group, [&] {
      if (!out)
      {
        throw InvalidInputException("ComputeObjectiveSensitivity needs an output array");
      }
      g = gradientValues(gradient, session.inputPoints().size(), "the gradient dJ/dX");
    });
    std::string method;
    const std::vector<double> dJdp = session.objectiveSensitivity(g, group, method);
    out->SetNumberOfComponents(1);
    out->SetNumberOfTuples(static_cast<vtkIdType>(dJdp.size()));
    std::copy(dJdp.begin(), dJdp.end(), out->GetPointer(0));
  });
}

bool vtkSubspaceDeformFilter::ComputeObjectiveSensitivities(vtkIdTypeArray* rows, vtkDoubleArray* values, vtkIdTypeArray* starts, vtkDoubleArray* out)
{
  return this->RunSensitivityRequest([&](const Collective& group) {
    DeformationSession& session = *this->Session;
    mlsvtk::SparseGradients g;
    agree(group, [&] {
      const vtkIdType n = static_cast<vtkIdType>(session.inputPoints().size());
      if (!rows || !values || !starts || !out || rows->GetNumberOfComponents() != 1 || values->GetNumberOfComponents() != 3 ||
        values->GetNumberOfTuples() != rows->GetNumberOfTuples() || starts->GetNumberOfTuples() < 2 || starts->GetValue(0) != 0 ||
        starts->GetValue(starts->GetNumberOfTuples() - 1) != rows->GetNumberOfTuples())
      {
        throw InvalidInputException("ComputeObjectiveSensitivities needs rows (point indices), values (3 components, one tuple a row), "
                                    "starts (0, ..., the number of rows) and an output array");
      }
      for (vtkIdType f = 1; f < starts->GetNumberOfTuples(); ++f)
      {
        if (starts->GetValue(f) < starts->GetValue(f - 1))
        {
          throw InvalidInputException("ComputeObjectiveSensitivities: starts must not decrease");
        }
        g.starts.push_back(starts->GetValue(f));
      }
      for (vtkIdType e = 0; e < rows->GetNumberOfTuples(); ++e)
      {
        if (rows->GetValue(e) < 0 || rows->GetValue(e) >= n)
        {
          throw InvalidInputException("ComputeObjectiveSensitivities: a row is not a point of the output (0 .. " + std::to_string(n - 1) + ")");
        }
        g.rows.push_back(rows->GetValue(e));
      }
      g.values.assign(values->GetPointer(0), values->GetPointer(0) + 3 * values->GetNumberOfTuples());
      requireFiniteValues(g.values, "the gradients");
    });
    std::string method;
    const std::vector<std::vector<double>> dJdp = session.objectiveSensitivities(std::move(g), group, method);
    out->SetNumberOfComponents(static_cast<int>(std::max<std::size_t>(1, session.design().size())));
    out->SetNumberOfTuples(static_cast<vtkIdType>(dJdp.size()));
    for (std::size_t f = 0; f < dJdp.size(); ++f)
    {
      std::copy(dJdp[f].begin(), dJdp[f].end(), out->GetPointer(0) + f * out->GetNumberOfComponents());
    }
  });
}

bool vtkSubspaceDeformFilter::ComputeMeshQualityAggregate(int measure, double rho, vtkDoubleArray* value, vtkIdTypeArray* rows, vtkDoubleArray* gradient)
{
  return this->RunSensitivityRequest([&](const Collective& group) {
    agree(group, [&] {
      if (!value || !rows != !gradient || measure < 0 || measure > 2 || !std::isfinite(rho) || rho <= 0)
      {
        throw InvalidInputException("ComputeMeshQualityAggregate needs measure 0 (non-orthogonality), 1 (skewness) or 2 (the scaled "
                                    "Jacobian), a positive finite rho, an output array, and rows with the gradient or neither");
      }
      if (!this->MeshQuality)
      {
        throw InvalidInputException("the mesh quality aggregate needs MeshQuality on (the faces it measures are found there)");
      }
    });
    std::vector<double> g;
    const auto result = this->Session->qualityAggregate(static_cast<mlsdeform::QualityMeasure>(measure), rho, group, gradient ? &g : nullptr);
    value->SetNumberOfComponents(1);
    value->SetNumberOfTuples(2);
    value->SetValue(0, result.value);
    value->SetValue(1, static_cast<double>(result.count));
    if (gradient)
    {
      writeNonZeroRows(g.data(), nullptr, g.size() / 3, rows, gradient);
    }
  });
}

struct vtkSubspaceDeformFilter::MeshVolumes
{
  std::string set;
  Stamp stamp; // of the output's cells, the input's points and the set's arrays they were found on
  std::vector<std::unique_ptr<MeshVolume>> grids; // per output set (null: not a grid)
};

bool vtkSubspaceDeformFilter::ComputeMeshVolume(const char* cellSet, vtkDoubleArray* value, vtkIdTypeArray* rows, vtkDoubleArray* gradient)
{
  return this->RunSensitivityRequest([&](const Collective& group) {
    const std::string set = cellSet ? cellSet : "";
    agree(group, [&] {
      if (!value || !rows != !gradient)
      {
        throw InvalidInputException("ComputeMeshVolume needs an output array, and rows with the gradient or neither");
      }
    });
    const std::vector<vtkPointSet*> outSets = pointSets(this->GetOutputDataObject(0));
    const std::vector<vtkPointSet*> inSets = pointSets(this->GetInputDataObject(0, 0));
    const PointList& rest = this->Session->inputPoints();
    const std::size_t n = rest.size();
    Stamp stamp = cellsStamp(outSets);
    const Stamp restPoints = pointsStamp(inSets);
    stamp.objects.insert(stamp.objects.end(), restPoints.objects.begin(), restPoints.objects.end());
    for (vtkPointSet* points : outSets)
    {
      stamp.add(set.empty() ? nullptr : points->GetCellData()->GetArray(set.c_str()));
    }
    double named = set.empty() ? 1 : 0;
    if (!this->Volumes || this->Volumes->set != set || this->Volumes->stamp != stamp)
    {
      auto volumes = std::make_unique<MeshVolumes>();
      volumes->set = set;
      volumes->stamp = stamp;
      const bool femReader = femReaderUpstream(this);
      std::size_t offset = 0;
      for (vtkPointSet* points : outSets)
      {
        const auto m = static_cast<std::size_t>(points->GetNumberOfPoints());
        auto* grid = vtkUnstructuredGrid::SafeDownCast(points);
        vtkDataArray* in = set.empty() || !grid ? nullptr : grid->GetCellData()->GetArray(set.c_str());
        std::vector<char> selected(in ? static_cast<std::size_t>(grid->GetNumberOfCells()) : 0, 0);
        for (std::size_t c = 0; c < selected.size(); ++c)
        {
          selected[c] = in->GetTuple1(static_cast<vtkIdType>(c)) != 0 ? 1 : 0;
        }
        const bool measured = grid && offset + m <= n && (set.empty() || in);
        volumes->grids.push_back(measured ? std::make_unique<MeshVolume>(grid,
          PointList(rest.begin() + static_cast<long>(offset), rest.begin() + static_cast<long>(offset + m)), selected,
          femReader || femVerdictOf(grid), static_cast<int>(offset)) : nullptr);
        offset += m;
      }
      this->Volumes = std::move(volumes);
    }
    const PointList& deformed = this->Session->deformedPoints();
    std::vector<int> at; // the grids' gradient rows (their points apart: ascending) and values
    PointList g;
    double volume = 0, cells = 0;
    for (const std::unique_ptr<MeshVolume>& grid : this->Volumes->grids)
    {
      if (grid)
      {
        named = 1;
        std::vector<int> gridRows;
        PointList gridGradient;
        volume += grid->volume(deformed, gradient ? &gridRows : nullptr, &gridGradient);
        at.insert(at.end(), gridRows.begin(), gridRows.end());
        g.insert(g.end(), gridGradient.begin(), gridGradient.end());
        cells += static_cast<double>(grid->cells());
      }
    }
    // every process's sums, added in process order: the same on every process
    const std::vector<double> parts = group.gather(std::vector<double>{ volume, cells, named });
    volume = cells = named = 0;
    for (std::size_t r = 0; r + 2 < parts.size(); r += 3)
    {
      volume += parts[r];
      cells += parts[r + 1];
      named = std::max(named, parts[r + 2]);
    }
    if (named == 0)
    {
      throw InvalidInputException("no volume mesh has the cell array '" + set + "' (a cell set: a deck's element set)");
    }
    if (cells == 0)
    {
      throw InvalidInputException(set.empty() ? std::string("the output has no volume cells (3D cells of an unstructured grid)")
                                              : "the cell set '" + set + "' holds no volume cell");
    }
    value->SetNumberOfComponents(1);
    value->SetNumberOfTuples(2);
    value->SetValue(0, volume);
    value->SetValue(1, cells);
    if (gradient)
    {
      static_assert(sizeof(Vec3) == 3 * sizeof(double), "points as packed doubles");
      writeNonZeroRows(g.empty() ? nullptr : g.front().data(), at.data(), g.size(), rows, gradient);
    }
  });
}

struct vtkSubspaceDeformFilter::MeasuredSurfaces
{
  struct Entry
  {
    vtkIdTypeArray* polygons; // the array (kept by the caller) and its time: a new array has a new one
    vtkMTimeType time;
    mlsdeform::PolygonSurface surface;
  };
  std::vector<Entry> recent; // the last few, the latest first (a design's constraints measure a few surfaces)
};

template <typename Measure>
bool vtkSubspaceDeformFilter::ComputeSurfaceMeasure(const std::string& problem, const char* name, vtkIdTypeArray* polygons,
  vtkDoubleArray* value, vtkIdTypeArray* rows, vtkDoubleArray* gradient, Measure measure)
{
  return this->RunSensitivityRequest([&](const Collective& group) {
    const PointList& deformed = this->Session->deformedPoints();
    if (!this->Surfaces)
    {
      this->Surfaces = std::make_unique<MeasuredSurfaces>();
    }
    std::vector<MeasuredSurfaces::Entry>& recent = this->Surfaces->recent;
    auto hit = std::find_if(recent.begin(), recent.end(), [&](const MeasuredSurfaces::Entry& e) {
      return polygons && e.polygons == polygons && e.time == polygons->GetMTime();
    });
    agree(group, [&] {
      if (!problem.empty())
      {
        throw InvalidInputException(problem);
      }
      if (!value || !rows != !gradient || !polygons || (polygons->GetNumberOfTuples() > 0 && polygons->GetNumberOfComponents() < 3))
      {
        throw InvalidInputException(std::string(name) + " needs polygons (a tuple of at least 3 point indices each), an output "
                                    "array, and rows with the gradient or neither");
      }
      if (hit == recent.end())
      {
        const auto m = static_cast<std::size_t>(polygons->GetNumberOfTuples());
        const auto n = static_cast<std::size_t>(polygons->GetNumberOfComponents());
        std::vector<long> starts(m + 1);
        std::vector<int> corners(m * n);
        for (std::size_t k = 0; k < m * n; ++k)
        {
          const vtkIdType p = polygons->GetValue(static_cast<vtkIdType>(k));
          if (p < 0 || static_cast<std::size_t>(p) >= deformed.size())
          {
            throw InvalidInputException(std::string(name) + ": polygon " + std::to_string(k / n) + " has the point " + std::to_string(p) +
                                        ", not one of the output's " + std::to_string(deformed.size()) + " points");
          }
          corners[k] = static_cast<int>(p);
        }
        for (std::size_t f = 0; f <= m; ++f)
        {
          starts[f] = static_cast<long>(f * n);
        }
        recent.insert(recent.begin(), { polygons, polygons->GetMTime(), mlsdeform::PolygonSurface(starts, corners) });
        recent.erase(recent.begin() + static_cast<long>(std::min<std::size_t>(recent.size(), 4)), recent.end());
        hit = recent.begin();
      }
      if (hit->surface.pointsNeeded() > deformed.size()) // found on another output
      {
        throw InvalidInputException(std::string(name) + ": the polygons name the point " + std::to_string(hit->surface.pointsNeeded() - 1) +
                                    ", not one of the output's " + std::to_string(deformed.size()) + " points");
      }
    });
    std::rotate(recent.begin(), hit, hit + 1);
    const mlsdeform::PolygonSurface& surface = recent.front().surface;
    PointList g;
    const double local = measure(surface, deformed, gradient ? &g : nullptr);
    // every process's sums, added in process order: the same on every process
    const std::vector<double> parts = group.gather(std::vector<double>{ local, static_cast<double>(surface.polygons()) });
    double total = 0, count = 0;
    for (std::size_t r = 0; r + 1 < parts.size(); r += 2)
    {
      total += parts[r];
      count += parts[r + 1];
    }
    value->SetNumberOfComponents(1);
    value->SetNumberOfTuples(2);
    value->SetValue(0, total);
    value->SetValue(1, count);
    if (gradient)
    {
      writeNonZeroRows(g.empty() ? nullptr : g.front().data(), surface.points().data(), g.size(), rows, gradient);
    }
  });
}

bool vtkSubspaceDeformFilter::ComputeSurfaceVolume(vtkIdTypeArray* polygons, const double axis[3], vtkDoubleArray* value,
  vtkIdTypeArray* rows, vtkDoubleArray* gradient)
{
  const Vec3 a = axis ? Vec3(axis[0], axis[1], axis[2]) : Vec3::Zero();
  return this->ComputeSurfaceMeasure(a.allFinite() ? "" : "ComputeSurfaceVolume needs a finite axis (zero: a closed surface)",
    "ComputeSurfaceVolume", polygons, value, rows, gradient,
    [&](const mlsdeform::PolygonSurface& surface, const PointList& points, PointList* g) {
      // closed: V = 1/3 sum_f C_f . S_f; extruded along a: V = 1/2 sum_f (P C_f) . S_f, P = I - a a^T
      const bool extruded = a.norm() > 0;
      const Vec3 u = extruded ? Vec3(a.normalized()) : Vec3::Zero();
      return surface.volume(points, Eigen::Matrix3d::Identity() - u * u.transpose(), extruded ? 0.5 : 1.0 / 3, g);
    });
}

bool vtkSubspaceDeformFilter::ComputeSurfaceArea(vtkIdTypeArray* polygons, vtkDoubleArray* value, vtkIdTypeArray* rows,
  vtkDoubleArray* gradient)
{
  return this->ComputeSurfaceMeasure("", "ComputeSurfaceArea", polygons, value, rows, gradient,
    [](const mlsdeform::PolygonSurface& surface, const PointList& points, PointList* g) { return surface.area(points, g); });
}

int vtkSubspaceDeformFilter::GetNumberOfSamplings()
{
  return this->Session->runs().subspace;
}

int vtkSubspaceDeformFilter::GetNumberOfPointEvaluations()
{
  return this->Session->runs().pointRows;
}

int vtkSubspaceDeformFilter::GetNumberOfTargetSetups()
{
  return this->Session->runs().targets;
}

int vtkSubspaceDeformFilter::GetNumberOfConstraintSetups()
{
  return this->Session->runs().constraints;
}

int vtkSubspaceDeformFilter::GetNumberOfFactorizations()
{
  return this->Session->runs().factorization;
}

int vtkSubspaceDeformFilter::GetNumberOfSolves()
{
  return this->Session->runs().solve;
}

void vtkSubspaceDeformFilter::PrefetchCaseFaces(const char* casePath)
{
  if (casePath && *casePath)
  {
    mlsvtk::prefetchCaseFaces(casePath);
  }
}

void vtkSubspaceDeformFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "StretchWeight: " << this->StretchWeight << "\n"
     << indent << "BendWeight: " << this->BendWeight << "\n"
     << indent << "FixWeight: " << this->FixWeight << "\n"
     << indent << "ConstraintWeight: " << this->ConstraintWeight << "\n"
     << indent << "ExactTargets: " << this->ExactTargets << "\n"
     << indent << "TargetBlendRadius: " << this->TargetBlendRadius << "\n"
     << indent << "ExactConstraints: " << this->ExactConstraints << "\n"
     << indent << "ConstraintFormulation: " << this->ConstraintFormulation << "\n"
     << indent << "MaxIterations: " << this->MaxIterations << "\n"
     << indent << "Tolerance: " << this->Tolerance << "\n"
     << indent << "Acceleration: " << this->Acceleration << "\n"
     << indent << "ExtrusionAxis: " << this->ExtrusionAxis << "\n"
     << indent << "MeshQuality: " << this->MeshQuality << "\n"
     << indent << "ComputeSensitivities: " << this->ComputeSensitivities << "\n"
     << indent << "ObjectiveGradientArray: " << (this->ObjectiveGradientArray ? this->ObjectiveGradientArray : "(none)") << "\n";
}
