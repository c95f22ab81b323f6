// The fandisk deformation of deform_fandisk.py as a plain VTK C++ pipeline:
//   vtkOFFReader -> vtkConstraintRegion (fixed bottom, moved top) -> vtkMLSDeformFilter -> .vtp
// Usage: DeformFandisk fandisk.off output.vtp
#include "FandiskScene.h"
#include "vtkMLSDeformFilter.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdio>

int main(int argc, char* argv[])
{
  if (argc != 3)
  {
    std::fprintf(stderr, "usage: %s input.off output.vtp\n", argv[0]);
    return 2;
  }
  FandiskScene scene;
  if (!scene.open(argv[1]))
  {
    return 1;
  }
  // the handle moved along -x by 15% of the height
  const double height = scene.height;
  scene.handle->SetTranslation(-0.15 * height, 0, 0);
  vtkOFFReader* reader = scene.reader;
  vtkConstraintRegion *fixed = scene.fixed, *handle = scene.handle;

  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputConnection(reader->GetOutputPort());
  deform->AddRegionConnection(fixed->GetOutputPort());
  deform->AddRegionConnection(handle->GetOutputPort());

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(deform->GetOutputPort());
  writer->SetFileName(argv[2]);
  if (!writer->Write())
  {
    return 1;
  }
  vtkFieldData* field = deform->GetOutputDataObject(0)->GetFieldData();
  auto value = [field](const char* name) { return field->GetArray(name) ? field->GetArray(name)->GetTuple1(0) : -1.0; };
  std::printf("fandisk: %lld points, k = %g, N = %g, set-up %.2f s, solve %.1f ms, handle residual %.3g, fixed residual %.3g "
              "(handle moved by %.3g)\nwrote %s\n",
    static_cast<long long>(reader->GetOutput()->GetNumberOfPoints()), value("NumberOfSamples"), value("NumberOfIntegrationPoints"),
    value("SetupTime"), 1000 * value("SolveTime"), value("HandleResidual"), value("FixedResidual"), 0.15 * height, argv[2]);
  return value("HandleResidual") >= 0 ? 0 : 1;
}
