// The fandisk deformation of deform_fandisk.py as a plain VTK C++ pipeline:
//   vtkOFFReader -> vtkConstraintRegion (fixed bottom, moved top) -> vtkMLSDeformFilter -> .vtp
// Usage: DeformFandisk fandisk.off output.vtp
#include "vtkConstraintRegion.h"
#include "vtkMLSDeformFilter.h"
#include "vtkOFFReader.h"

#include <vtkBox.h>
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
  vtkNew<vtkOFFReader> reader;
  reader->SetFileName(argv[1]);
  reader->Update();
  if (reader->GetOutput()->GetNumberOfPoints() == 0)
  {
    return 1;
  }
  double b[6];
  reader->GetOutput()->GetBounds(b);
  const double height = b[5] - b[4], margin = 0.01 * height;

  // Fixed: the bottom 10%. Handle: the top 25%, moved along -x by 15% of the height.
  vtkNew<vtkBox> bottom, top;
  bottom->SetBounds(b[0] - margin, b[1] + margin, b[2] - margin, b[3] + margin, b[4] - margin, b[4] + 0.1 * height);
  top->SetBounds(b[0] - margin, b[1] + margin, b[2] - margin, b[3] + margin, b[5] - 0.25 * height, b[5] + margin);
  vtkNew<vtkConstraintRegion> fixed, handle;
  fixed->SetInputConnection(reader->GetOutputPort());
  fixed->SetRole(vtkConstraintRegion::Fixed);
  fixed->SetRegion(bottom);
  handle->SetInputConnection(reader->GetOutputPort());
  handle->SetRole(vtkConstraintRegion::Handle);
  handle->SetRegion(top);
  handle->SetTranslation(-0.15 * height, 0, 0);

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
