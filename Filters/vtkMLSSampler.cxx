#include "vtkMLSSampler.h"

#include "Sampling/Sampling.h"
#include "Adapters/PointSets.h"
#include "Adapters/MeshCells.h"
#include "Adapters/AlgorithmProgress.h"
#include "Adapters/FailurePolicy.h"
#include "Adapters/ProcessCollective.h"
#include "Adapters/ReportArrays.h"
#include "Vocabulary/FieldNames.h"

#include <vtkDataObject.h>
#include <vtkErrorCode.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

vtkStandardNewMacro(vtkMLSSampler);

vtkMLSSampler::vtkMLSSampler()
{
  this->SetNumberOfOutputPorts(2);
  this->SetProgressText("MLS Sampler");
}

int vtkMLSSampler::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

int vtkMLSSampler::RequestData(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const mlsvtk::ReportArrays reports(inputVector[0], outputVector); // its field data: reports, not fields
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkPolyData* centersOut = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* integrationOut = vtkPolyData::GetData(outputVector, 1);
  this->SetErrorCode(vtkErrorCode::NoError);
  mlsdeform::SamplingParameters parameters;
  parameters.numberOfSurfaceSamples = this->NumberOfSurfaceSamples;
  parameters.numberOfVolumeSamples = this->NumberOfVolumeSamples;
  mlsvtk::copySamplingProperties(this, parameters);
  parameters.surfaceWeight = this->SurfaceWeight;
  parameters.denseSamplesPerSample = this->DenseSamplesPerSample;
  parameters.boundsPadding = this->BoundsPadding;
  try
  {
    // Split over processes, the samples of the whole input are computed by all of them together
    // and given out once, by the first (MLS Deform gathers its Samples input from every process).
    const mlsvtk::ProcessCollective group;
    const mlsdeform::SamplingDomain domain = mlsvtk::samplingDomain(mlsvtk::pointSets(input), group);
    const mlsdeform::Samples samples = mlsdeform::sampleDomain(domain, parameters, mlsvtk::progressOf(this, 0, 1, group), group);
    mlsvtk::checkAbort(this, group);
    if (group.rank() > 0)
    {
      return 1;
    }
    if (static_cast<int>(samples.centers.size()) < this->NumberOfSurfaceSamples + this->NumberOfVolumeSamples)
    {
      vtkWarningMacro(<< "Only " << samples.centers.size() << " distinct MLS samples could be placed.");
    }
    std::vector<double> onSurface(samples.centers.size(), 0.0);
    std::fill(onSurface.begin(), onSurface.begin() + samples.numberOfSurfaceCenters, 1.0);
    centersOut->ShallowCopy(mlsvtk::pointCloud(samples.centers, { { mlsvtk::fields::SupportRadius, &samples.supportRadius }, { mlsvtk::fields::OnSurface, &onSurface } }));
    integrationOut->ShallowCopy(mlsvtk::pointCloud(samples.integrationPoints, { { mlsvtk::fields::Volume, &samples.volume } }));
  }
  catch (const std::exception& e)
  {
    centersOut->Initialize();
    integrationOut->Initialize();
    this->SetErrorCode(vtkErrorCode::UserError);
    return mlsvtk::reportFailure(this, outputVector, e, "The outputs are empty.", "cannot sample the input: ");
  }
  return 1;
}

void vtkMLSSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSurfaceSamples: " << this->NumberOfSurfaceSamples << "\n"
     << indent << "NumberOfVolumeSamples: " << this->NumberOfVolumeSamples << "\n";
  mlsvtk::printSamplingProperties(this, os, indent);
  os << indent << "SurfaceWeight: " << this->SurfaceWeight << "\n"
     << indent << "DenseSamplesPerSample: " << this->DenseSamplesPerSample << "\n"
     << indent << "BoundsPadding: " << this->BoundsPadding << "\n";
}
