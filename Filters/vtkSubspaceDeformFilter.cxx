#include "vtkSubspaceDeformFilter.h"

#include "Adapters/FailurePolicy.h"
#include "Adapters/PointSets.h"
#include "Adapters/ProcessCollective.h"
#include "Session/DeformationSession.h"
#include "Session/SolutionReport.h"

#include <vtkDataObject.h>
#include <vtkErrorCode.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>

#include <chrono>

using namespace mlsdeform;
using namespace mlsvtk;

namespace
{
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

vtkSubspaceDeformFilter::~vtkSubspaceDeformFilter() = default;

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
  try
  {
    SolutionFigures figures;
    const auto setupStart = Clock::now();
    session.readInputs(inSets, inputVector[1], group);
    figures.resampled = session.updateSubspace(this->GetSubspaceDependencies(inputVector), inSets,
      [&] { return this->BuildSubspace(inSets, inputVector); }, group);
    session.updatePointRows(group);
    session.updateTargets();
    session.updateConstraints(static_cast<mlsdeform::ConstraintFormulation>(this->ConstraintFormulation));
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
    session.writeOutput(inSets, outSets, solution);
    figures.solveTime = secondsSince(solveStart);
    figures.setupTime = session.setupTime();
    figures.diagonal = session.diagonal();

    const double constraintResidual = reportSolution(output->GetFieldData(), session.model(), session.regions(), solution, figures);
    if (this->MeshQuality)
    {
      session.reportQuality(inSets, outSets, output->GetFieldData(), group);
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
    copyInput(input, output);
    this->SetErrorCode(vtkErrorCode::UserError);
    return reportFailure(this, outputVector, e.what(), "The output is the unchanged input.");
  }
  return 1;
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
