#include "vtkMLSDeformFilter.h"

#include "Common/BoundingBox.h"
#include "Common/GatheredPositions.h"
#include "Session/SubspaceDependencies.h"
#include "Adapters/PointSets.h"
#include "Adapters/MeshCells.h"
#include "Adapters/AlgorithmProgress.h"
#include "Adapters/ProcessCollective.h"
#include "Vocabulary/FieldNames.h"
#include "Basis/ShellOperators.h"
#include "Solver/SpaceDeformation.h"

#include <vtkInformationVector.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>

#include <cmath>

using namespace mlsdeform;

vtkStandardNewMacro(vtkMLSDeformFilter);

namespace
{
// Positions with one value each (a point array) from all processes, in the canonical order of
// GatheredPositions.h: replicated or split samples give every process the same list.
void gatherWithValues(vtkPolyData* data, vtkDataArray* array, PointList& positions, std::vector<double>& values, const Collective& group)
{
  std::vector<double> local(static_cast<std::size_t>(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    local[i] = array->GetTuple1(i);
  }
  const mlsdeform::GatheredPositions gathered = mlsdeform::gatherPositions(mlsvtk::points({ data }), {}, group);
  positions = gathered.positions;
  values = mlsdeform::gatherValues(local.data(), static_cast<long>(local.size()), 1, gathered, group);
}

Samples readSamples(vtkPolyData* centers, vtkPolyData* integration, const Collective& group)
{
  vtkDataArray* radius = centers && integration ? centers->GetPointData()->GetArray(mlsvtk::fields::SupportRadius) : nullptr;
  vtkDataArray* volume = centers && integration ? integration->GetPointData()->GetArray(mlsvtk::fields::Volume) : nullptr;
  agree(group, [&] {
    if (!integration)
    {
      throw InvalidInputException("MLS samples were given without integration points (connect both outputs of MLSSampler)");
    }
    if (!radius || !volume || radius->GetNumberOfTuples() != centers->GetNumberOfPoints() ||
      volume->GetNumberOfTuples() != integration->GetNumberOfPoints())
    {
      throw InvalidInputException("the Samples input needs a SupportRadius array and the IntegrationPoints input a Volume array");
    }
  });
  Samples samples;
  gatherWithValues(centers, radius, samples.centers, samples.supportRadius, group);
  gatherWithValues(integration, volume, samples.integrationPoints, samples.volume, group);
  return samples;
}


// The internal sampling's parameters from the properties: the one list that gives both the
// subspace's cache key and the sampler's parameters.
SamplingParameters samplingParameters(vtkMLSDeformFilter* filter)
{
  SamplingParameters parameters;
  parameters.numberOfVolumeSamples = static_cast<int>(std::lround(filter->GetVolumeSampleFraction() * filter->GetNumberOfSamples()));
  parameters.numberOfSurfaceSamples = filter->GetNumberOfSamples() - parameters.numberOfVolumeSamples;
  mlsvtk::copySamplingProperties(filter, parameters);
  return parameters;
}
}

vtkMLSDeformFilter::vtkMLSDeformFilter()
  : vtkSubspaceDeformFilter(4)
{
  this->SetProgressText("MLS Deform");
}

mlsvtk::SubspaceDependencies vtkMLSDeformFilter::GetSubspaceDependencies(vtkInformationVector** inputVector)
{
  vtkPolyData* externalCenters = vtkPolyData::GetData(inputVector[2], 0);
  vtkPolyData* externalIntegration = vtkPolyData::GetData(inputVector[3], 0);
  mlsvtk::SubspaceDependencies dependencies;
  dependencies.settings = { static_cast<double>(this->Basis), static_cast<double>(this->EnergyDiscretization) };
  if (externalCenters)
  {
    // the samples and integration points with their arrays; the input's mesh only for its energies
    for (vtkPolyData* samples : { externalCenters, externalIntegration })
    {
      dependencies.inputs.add(samples ? samples->GetPoints() : nullptr);
      dependencies.inputs.add(samples ? samples->GetPointData() : nullptr);
    }
    dependencies.geometry = this->EnergyDiscretization == SurfaceVertices;
  }
  else
  {
    const std::vector<double> sampling = samplingParameters(this).key();
    dependencies.settings.insert(dependencies.settings.end(), sampling.begin(), sampling.end());
  }
  return dependencies;
}

std::unique_ptr<SpaceDeformation> vtkMLSDeformFilter::BuildSubspace(const std::vector<vtkPointSet*>& inSets, vtkInformationVector** inputVector)
{
  vtkPolyData* externalCenters = vtkPolyData::GetData(inputVector[2], 0);
  vtkPolyData* externalIntegration = vtkPolyData::GetData(inputVector[3], 0);
  const mlsvtk::ProcessCollective group;
  Samples samples;
  if (externalCenters)
  {
    samples = readSamples(externalCenters, externalIntegration, group);
  }
  else
  {
    vtkLogScopeF(TRACE, "MLS Deform: sampling");
    samples = sampleDomain(mlsvtk::samplingDomain(inSets, group), samplingParameters(this), mlsvtk::progressOf(this, 0.0, 0.4, group), group);
  }
  const BasisKind kind = static_cast<BasisKind>(this->Basis);
  if (this->EnergyDiscretization == SurfaceVertices)
  {
    // eq. 11: the shell energy of the input's triangles with d = Phi w at its vertices
    if (group.size() > 1)
    {
      throw InvalidInputException("EnergyDiscretization SurfaceVertices integrates on the whole surface mesh and runs on one process only (use Volumetric)");
    }
    const SamplingDomain mesh = mlsvtk::samplingDomain(inSets);
    if (!mesh.tetrahedra.empty())
    {
      throw InvalidInputException("EnergyDiscretization SurfaceVertices integrates on triangle surfaces; this input has volume cells (use Volumetric)");
    }
    std::shared_ptr<const ShapeFunctions> basis = makeBasis(kind, samples);
    DeformationEnergy energy = surfaceVertexEnergy(*basis, mesh);
    return std::make_unique<SpaceDeformation>(std::move(basis), std::move(energy), largestSide(mesh.points));
  }
  vtkLogScopeF(TRACE, "MLS Deform: basis and energy operators");
  return std::make_unique<SpaceDeformation>(samples, kind, mlsvtk::progressOf(this, 0.4, 0.6, group));
}

void vtkMLSDeformFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSamples: " << this->NumberOfSamples << "\n"
     << indent << "VolumeSampleFraction: " << this->VolumeSampleFraction << "\n";
  mlsvtk::printSamplingProperties(this, os, indent);
  os << indent << "Basis: " << this->Basis << "\n"
     << indent << "EnergyDiscretization: " << this->EnergyDiscretization << "\n";
}
