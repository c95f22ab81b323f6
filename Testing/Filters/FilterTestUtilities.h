// Scenes and helpers shared by the VTK algorithm tests.
#pragma once

#include "vtkConstraintRegion.h"
#include "vtkMLSDeformFilter.h"
#include "vtkShellDeformFilter.h"

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
#include <vtkTrivialProducer.h>
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

/// The box [0,2] x [0,1] x [0,1] as image data with n cells per unit length.
inline vtkSmartPointer<vtkImageData> boxImage(int n)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(2 * n + 1, n + 1, n + 1);
  image->SetSpacing(1.0 / n, 1.0 / n, 1.0 / n);
  return image;
}

/// A tetrahedral mesh of the box [0,2] x [0,1] x [0,1] (n cells per unit length).
inline vtkSmartPointer<vtkUnstructuredGrid> tetrahedralBox(int n)
{
  vtkSmartPointer<vtkImageData> image = boxImage(n);
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

const double FixedBox[6] = { -0.1, 0.1, -0.1, 1.1, -0.1, 0.1 };  // strip x <= 0.1
const double HandleBox[6] = { 0.9, 1.1, -0.1, 1.1, -0.1, 0.1 };  // strip x >= 0.9
const double Lift = 0.3;

/// The scene of Fig. 1 for a deformation filter: geometry, a fixed strip x <= 0.1, a handle strip
/// x >= 0.9 lifted by Lift.
template <typename DeformFilter>
struct FigureScene
{
  vtkNew<vtkTrivialProducer> source;
  vtkSmartPointer<vtkConstraintRegion> fixed, handle;
  vtkNew<DeformFilter> deform;
  explicit FigureScene(vtkDataObject* geometry)
  {
    source->SetOutput(geometry);
    fixed = boxRegion(source->GetOutputPort(), vtkConstraintRegion::Fixed, FixedBox);
    handle = boxRegion(source->GetOutputPort(), vtkConstraintRegion::Handle, HandleBox);
    handle->SetTranslation(0, 0, Lift);
    deform->SetInputConnection(source->GetOutputPort());
    deform->AddRegionConnection(fixed->GetOutputPort());
    deform->AddRegionConnection(handle->GetOutputPort());
  }
};

// Distances of a strip's points from their targets (lifted by lift), measured on the output.
struct TargetError
{
  double max = 0, rms = 0;
};
inline TargetError targetError(vtkPointSet* input, vtkPointSet* output, const double box[6], double lift)
{
  TargetError error;
  int count = 0;
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    double x[3], y[3];
    input->GetPoint(i, x);
    output->GetPoint(i, y);
    if (x[0] >= box[0] && x[0] <= box[1])
    {
      const double e2 = (y[0] - x[0]) * (y[0] - x[0]) + (y[1] - x[1]) * (y[1] - x[1]) + (y[2] - x[2] - lift) * (y[2] - x[2] - lift);
      error.max = std::max(error.max, std::sqrt(e2));
      error.rms += e2;
      ++count;
    }
  }
  error.rms = std::sqrt(error.rms / count);
  return error;
}

// Sum of squared second differences of the height along the middle row y = 0.5 (33 samples).
inline double profileRoughness(vtkPointSet* output)
{
  std::vector<double> z;
  for (vtkIdType i = 16 * 33; i < 17 * 33; ++i)
    z.push_back(output->GetPoint(i)[2]);
  double roughness = 0;
  for (std::size_t i = 1; i + 1 < z.size(); ++i)
    roughness += std::pow(z[i - 1] - 2 * z[i] + z[i + 1], 2);
  return roughness;
}
