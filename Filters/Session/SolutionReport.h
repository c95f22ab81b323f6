// What a deformation reports in its output's field data, so that a script can judge a variant:
// sizes, times, the targets' residuals, whether the set-up was rebuilt, and per constraint region
// its type, points, sets, residual, iterations and convergence.
#pragma once

#include "Session/RegionInputs.h"
#include "Solver/SpaceDeformation.h"

#include <string>
#include <vector>

class vtkFieldData;

namespace mlsvtk
{
/// One double named name in field.
void addField(vtkFieldData* field, const char* name, double value);

struct SolutionFigures
{
  double setupTime = 0, solveTime = 0; // seconds
  bool resampled = false, refactorized = false;
  double diagonal = 1; // of the bounding box of all processes' points: the constraint residuals' unit
  double targetCorrection = 0; // the largest residual of the penalty solution that exact targets made up
  std::string targetConflicts, constraintConflicts; // the regions that cannot hold exactly (DeformationSession)
};

/// Adds the figures of the solution of model for regions to field (one tuple per region of
/// constraints, the ones the model iterates on, in its order); returns the largest constraint
/// residual relative to the diagonal (0 without constraints).
double reportSolution(vtkFieldData* field, const mlsdeform::SpaceDeformation& model, const std::vector<RegionInput>& regions,
  const std::vector<const RegionInput*>& constraints, const mlsdeform::SpaceDeformation::Solution& solution,
  const SolutionFigures& figures);
} // namespace mlsvtk
