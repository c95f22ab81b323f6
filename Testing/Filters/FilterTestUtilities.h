// Scenes and helpers shared by the VTK algorithm tests.
#pragma once

#include "vtkConstraintRegion.h"
#include "vtkMLSDeformFilter.h"

#include <vtkAlgorithmOutput.h>
#include <vtkBox.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDataSetTriangleFilter.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <string>
#include <vector>

/// Collects error and warning messages of an algorithm instead of printing them.
class MessageCollector : public vtkCommand
{
public:
  static MessageCollector* New() { return new MessageCollector; }
  void Execute(vtkObject*, unsigned long event, void* data) override
  {
    (event == vtkCommand::ErrorEvent ? Errors : Warnings).push_back(static_cast<const char*>(data));
  }
  static vtkSmartPointer<MessageCollector> watch(vtkObject* object)
  {
    auto collector = vtkSmartPointer<MessageCollector>::New();
    object->AddObserver(vtkCommand::ErrorEvent, collector);
    object->AddObserver(vtkCommand::WarningEvent, collector);
    return collector;
  }
  bool errorContains(const std::string& text) const
  {
    for (const std::string& e : Errors)
      if (e.find(text) != std::string::npos)
        return true;
    return false;
  }
  std::vector<std::string> Errors, Warnings;
};

/// The plane of Fig. 1: [0,1]^2 in z = 0 with 33 x 33 = 1089 vertices.
inline vtkSmartPointer<vtkPolyData> figurePlane()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(0, 0, 0);
  plane->SetPoint1(1, 0, 0);
  plane->SetPoint2(0, 1, 0);
  plane->SetResolution(32, 32);
  plane->Update();
  return plane->GetOutput();
}

/// A tetrahedral mesh of the box [0,2] x [0,1] x [0,1] (n cells per unit length).
inline vtkSmartPointer<vtkUnstructuredGrid> tetrahedralBox(int n)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(2 * n + 1, n + 1, n + 1);
  image->SetSpacing(1.0 / n, 1.0 / n, 1.0 / n);
  vtkNew<vtkDataSetTriangleFilter> tetrahedralize;
  tetrahedralize->SetInputData(image);
  tetrahedralize->Update();
  return tetrahedralize->GetOutput();
}

/// A region of the given role: the points inside the box [lower, upper].
inline vtkSmartPointer<vtkConstraintRegion> boxRegion(vtkAlgorithmOutput* input, int role, const double bounds[6])
{
  vtkNew<vtkBox> box;
  box->SetBounds(bounds);
  auto region = vtkSmartPointer<vtkConstraintRegion>::New();
  region->SetInputConnection(input);
  region->SetRole(role);
  region->SetRegion(box);
  return region;
}

inline double fieldValue(vtkDataObject* data, const char* name)
{
  vtkDataArray* array = data->GetFieldData()->GetArray(name);
  return array ? array->GetTuple1(0) : -1.0;
}
