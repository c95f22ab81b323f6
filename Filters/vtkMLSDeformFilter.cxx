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
#include <sstream>

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
}

std::string vtkMLSDeformFilter::SubspaceKey(const std::vector<vtkPointSet*>& inSets, vtkInformationVector** inputVector)
{
  vtkPolyData* externalCenters = vtkPolyData::GetData(inputVector[2], 0);
  vtkPolyData* externalIntegration = vtkPolyData::GetData(inputVector[3], 0);
  std::ostringstream key;
  if (externalCenters)
  {
    key << "external " << mlsgeometry::pointsSignature({ externalCenters }) << externalCenters->GetPointData()->GetMTime() << " "
        << (externalIntegration ? mlsgeometry::pointsSignature({ externalIntegration }) + std::to_string(externalIntegration->GetPointData()->GetMTime()) : "");
  }
  else
  {
    key << "internal " << mlsgeometry::pointsSignature(inSets) << mlsgeometry::cellsSignature(inSets) << this->NumberOfSamples << ' ' << this->VolumeSampleFraction << ' '
        << this->IntegrationPointRatio << ' ' << this->LloydIterations << ' ' << this->Cover << ' ' << this->RandomSeed;
  }
  key << " basis " << this->Basis << " energy " << this->EnergyDiscretization;
  return key.str();
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
     << indent << "Basis: " << this->Basis << "\n"
     << indent << "EnergyDiscretization: " << this->EnergyDiscretization << "\n";
}
