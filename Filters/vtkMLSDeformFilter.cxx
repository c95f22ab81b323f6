#include "vtkMLSDeformFilter.h"

#include "MLSGeometry.h"
#include "ShellOperators.h"
#include "SpaceDeformation.h"

#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>

#include <cmath>

using namespace mlsdeform;

vtkStandardNewMacro(vtkMLSDeformFilter);

namespace
{
Samples readSamples(vtkPolyData* centers, vtkPolyData* integration)
{
  if (!integration)
  {
    throw InvalidInputException("MLS samples were given without integration points (connect both outputs of MLSSampler)");
  }
  vtkDataArray* radius = centers->GetPointData()->GetArray("SupportRadius");
  vtkDataArray* volume = integration->GetPointData()->GetArray("Volume");
  if (!radius || !volume)
  {
    throw InvalidInputException("the Samples input needs a SupportRadius array and the IntegrationPoints input a Volume array");
  }
  Samples samples;
  samples.centers = mlsgeometry::points({ centers });
  samples.integrationPoints = mlsgeometry::points({ integration });
  for (vtkIdType i = 0; i < radius->GetNumberOfTuples(); ++i)
  {
    samples.supportRadius.push_back(radius->GetTuple1(i));
  }
  for (vtkIdType i = 0; i < volume->GetNumberOfTuples(); ++i)
  {
    samples.volume.push_back(volume->GetTuple1(i));
  }
  return samples;
}

}

vtkMLSDeformFilter::vtkMLSDeformFilter()
  : vtkSubspaceDeformFilter(4)
{
  this->SetProgressText("MLS Deform");
}

mlsgeometry::SubspaceDependencies vtkMLSDeformFilter::GetSubspaceDependencies(vtkInformationVector** inputVector)
{
  vtkPolyData* externalCenters = vtkPolyData::GetData(inputVector[2], 0);
  vtkPolyData* externalIntegration = vtkPolyData::GetData(inputVector[3], 0);
  mlsgeometry::SubspaceDependencies dependencies;
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
    dependencies.settings.insert(dependencies.settings.end(),
      { static_cast<double>(this->NumberOfSamples), this->VolumeSampleFraction, this->IntegrationPointRatio,
        static_cast<double>(this->LloydIterations), this->Cover, static_cast<double>(this->RandomSeed),
        static_cast<double>(this->FollowMeshGrading) });
  }
  return dependencies;
}

std::unique_ptr<SpaceDeformation> vtkMLSDeformFilter::BuildSubspace(const std::vector<vtkPointSet*>& inSets, vtkInformationVector** inputVector)
{
  vtkPolyData* externalCenters = vtkPolyData::GetData(inputVector[2], 0);
  vtkPolyData* externalIntegration = vtkPolyData::GetData(inputVector[3], 0);
  Samples samples;
  if (externalCenters)
  {
    samples = readSamples(externalCenters, externalIntegration);
  }
  else
  {
    SamplingParameters parameters;
    parameters.numberOfVolumeSamples = static_cast<int>(std::lround(this->VolumeSampleFraction * this->NumberOfSamples));
    parameters.numberOfSurfaceSamples = this->NumberOfSamples - parameters.numberOfVolumeSamples;
    parameters.integrationPointRatio = this->IntegrationPointRatio;
    parameters.lloydIterations = this->LloydIterations;
    parameters.cover = this->Cover;
    parameters.randomSeed = static_cast<std::uint64_t>(this->RandomSeed);
    parameters.followMeshGrading = this->FollowMeshGrading != 0;
    samples = sampleDomain(mlsgeometry::samplingDomain(inSets), parameters, { &mlsgeometry::reportProgress, this, 0.0, 0.4 });
  }
  const BasisKind kind = static_cast<BasisKind>(this->Basis);
  if (this->EnergyDiscretization == SurfaceVertices)
  {
    // eq. 11: the shell energy of the input's triangles with d = Phi w at its vertices
    const SamplingDomain mesh = mlsgeometry::samplingDomain(inSets);
    if (!mesh.tetrahedra.empty())
    {
      throw InvalidInputException("EnergyDiscretization SurfaceVertices integrates on triangle surfaces; this input has volume cells (use Volumetric)");
    }
    std::shared_ptr<const ShapeFunctions> basis = makeBasis(kind, samples);
    DeformationEnergy energy = surfaceVertexEnergy(*basis, mesh);
    return std::make_unique<SpaceDeformation>(std::move(basis), std::move(energy), largestSide(mesh.points));
  }
  return std::make_unique<SpaceDeformation>(samples, kind, mlsdeform::Progress{ &mlsgeometry::reportProgress, this, 0.4, 0.6 });
}

void vtkMLSDeformFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSamples: " << this->NumberOfSamples << "\n"
     << indent << "VolumeSampleFraction: " << this->VolumeSampleFraction << "\n"
     << indent << "IntegrationPointRatio: " << this->IntegrationPointRatio << "\n"
     << indent << "LloydIterations: " << this->LloydIterations << "\n"
     << indent << "Cover: " << this->Cover << "\n"
     << indent << "RandomSeed: " << this->RandomSeed << "\n"
     << indent << "FollowMeshGrading: " << this->FollowMeshGrading << "\n"
     << indent << "Basis: " << this->Basis << "\n"
     << indent << "EnergyDiscretization: " << this->EnergyDiscretization << "\n";
}
