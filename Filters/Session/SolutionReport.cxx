#include "Session/SolutionReport.h"

#include "Vocabulary/FieldNames.h"
#include "Vocabulary/RegionRoles.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkStringArray.h>

#include <algorithm>

using namespace mlsdeform;

namespace mlsvtk
{
void addField(vtkFieldData* field, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  field->AddArray(array);
}

namespace
{
// One tuple per constraint region: type, points, sets, residual (largest distance to the
// projection over its sets, relative to the bounding-box diagonal), iterations, converged.
// Returns the largest relative residual.
double reportConstraints(vtkFieldData* field, const std::vector<const RegionInput*>& constraints,
  const SpaceDeformation::Solution& solution, double diagonal)
{
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
    type->InsertNextValue(constraintName(*regionRole(r->role).constraint));
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
}

double reportSolution(vtkFieldData* field, const SpaceDeformation& model, const std::vector<RegionInput>& regions,
  const std::vector<const RegionInput*>& constraints, const SpaceDeformation::Solution& solution, const SolutionFigures& figures)
{
  // the RMS residual of each target region, in the order the regions were given (rmsResidual)
  double handleResidual = 0, fixedResidual = 0;
  std::size_t d = 0;
  for (const RegionInput& r : regions)
  {
    if (isConstraint(r.role))
    {
      continue;
    }
    double& residual = r.role == roles::Handle ? handleResidual : fixedResidual;
    residual = std::max(residual, solution.rmsResidual[d++]);
  }
  addField(field, "NumberOfSamples", static_cast<double>(model.basis().size()));
  addField(field, "NumberOfIntegrationPoints", static_cast<double>(model.numberOfIntegrationPoints()));
  addField(field, "SetupTime", figures.setupTime);
  addField(field, "SolveTime", figures.solveTime);
  addField(field, "HandleResidual", handleResidual);
  addField(field, "FixedResidual", fixedResidual);
  addField(field, "TargetCorrection", figures.targetCorrection);
  for (const auto& [name, text] : { std::make_pair(fields::TargetConflicts, &figures.targetConflicts),
         std::make_pair(fields::ConstraintConflicts, &figures.constraintConflicts) })
  {
    if (!text->empty())
    {
      vtkNew<vtkStringArray> conflicts;
      conflicts->SetName(name);
      conflicts->InsertNextValue(*text);
      field->AddArray(conflicts);
    }
  }
  addField(field, "ReciprocalCondition", model.reciprocalCondition());
  addField(field, "RegularizingStretchWeight", model.regularizingStretch());
  addField(field, "Resampled", figures.resampled ? 1 : 0);
  addField(field, "Refactorized", figures.refactorized ? 1 : 0);
  return reportConstraints(field, constraints, solution, figures.diagonal);
}
} // namespace mlsvtk
