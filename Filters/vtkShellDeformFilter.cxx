#include "vtkShellDeformFilter.h"

#include "Common/BoundingBox.h"
#include "Session/SubspaceDependencies.h"
#include "Adapters/MeshCells.h"
#include "Adapters/ProcessCollective.h"
#include "Basis/ShellOperators.h"
#include "Solver/SpaceDeformation.h"

#include <vtkObjectFactory.h>

using namespace mlsdeform;

vtkStandardNewMacro(vtkShellDeformFilter);

vtkShellDeformFilter::vtkShellDeformFilter()
  : vtkSubspaceDeformFilter(2)
{
  this->SetProgressText("Shell Deform");
}

mlsvtk::SubspaceDependencies vtkShellDeformFilter::GetSubspaceDependencies(vtkInformationVector**)
{
  return {}; // the mesh's points and cells only
}

std::unique_ptr<SpaceDeformation> vtkShellDeformFilter::BuildSubspace(const std::vector<vtkPointSet*>& inSets, vtkInformationVector**)
{
  if (mlsvtk::ProcessCollective().size() > 1)
  {
    throw InvalidInputException("Shell Deform's shape functions are the whole mesh's vertices: it runs on one process only");
  }
  const SamplingDomain mesh = mlsvtk::samplingDomain(inSets);
  this->UpdateProgress(0.1);
  DeformationEnergy energy = shellEnergy(mesh);
  this->UpdateProgress(0.5);
  return std::make_unique<SpaceDeformation>(std::make_shared<PiecewiseLinearBasis>(mesh.points), std::move(energy), largestSide(mesh.points));
}
