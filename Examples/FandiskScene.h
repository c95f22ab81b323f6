// The fandisk scene of the C++ examples (fandisk_scene.py is the Python examples'): the part
// read from an OFF file, its bottom 10% a Fixed region and its top 25% a Handle region.
#pragma once

#include "vtkConstraintRegion.h"
#include "vtkOFFReader.h"

#include <vtkBox.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

struct FandiskScene
{
  vtkNew<vtkOFFReader> reader;
  vtkNew<vtkBox> bottom, top;
  vtkNew<vtkConstraintRegion> fixed, handle;
  double bounds[6] = { 0, 0, 0, 0, 0, 0 };
  double height = 0;

  /// Reads the part and sets up the regions; false when the file holds no points.
  bool open(const char* path)
  {
    reader->SetFileName(path);
    reader->Update();
    if (reader->GetOutput()->GetNumberOfPoints() == 0)
    {
      return false;
    }
    const double* b = bounds;
    reader->GetOutput()->GetBounds(bounds);
    height = b[5] - b[4];
    const double margin = 0.01 * height;
    bottom->SetBounds(b[0] - margin, b[1] + margin, b[2] - margin, b[3] + margin, b[4] - margin, b[4] + 0.1 * height);
    top->SetBounds(b[0] - margin, b[1] + margin, b[2] - margin, b[3] + margin, b[5] - 0.25 * height, b[5] + margin);
    fixed->SetInputConnection(reader->GetOutputPort());
    fixed->SetRole(vtkConstraintRegion::Fixed);
    fixed->SetRegion(bottom);
    handle->SetInputConnection(reader->GetOutputPort());
    handle->SetRole(vtkConstraintRegion::Handle);
    handle->SetRegion(top);
    return true;
  }
};
