// Design variables and exact sensitivities on the fandisk, as a plain VTK C++ pipeline:
//   vtkOFFReader -> vtkConstraintRegion (fixed bottom; top handle with the design variables
//   "lift" and "tilt") -> vtkMLSDeformFilter (ComputeSensitivities) -> dJ/dp three ways.
// The objective J is the sum of the z coordinates of the handle's points, so dJ/dX = (0, 0, 1) on
// those points and 0 elsewhere. dJ/dp is computed in reverse mode (ComputeObjectiveSensitivity:
// one back-substitution for all variables), in forward mode (the output's dX/d<p> arrays summed
// over the handle's points) and by a central finite difference of J; the exit code is 1 when
// they disagree by more than the bounds below.
// Usage: DesignSensitivities fandisk.off
#include "FandiskScene.h"
#include "vtkMLSDeformFilter.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
// The design variables at the values p = {lift, tilt}: lift translates the top along z by 10% of
// the height per unit; tilt rotates it about the y axis through Center (the bottom's -x edge), one
// degree per unit. Bounds [-1, 1] and [-15, 15].
void setDesign(vtkConstraintRegion* handle, double height, const double p[2])
{
  handle->RemoveAllDesignVariables();
  handle->AddDesignVariable("lift", vtkConstraintRegion::TranslateVariable, 0, 0, 0.1 * height, p[0], -1, 1);
  handle->AddDesignVariable("tilt", vtkConstraintRegion::RotateVariable, 0, 1, 0, p[1], -15, 15);
}

// J = the sum of the z coordinates of the given points after the last update.
double objective(vtkMLSDeformFilter* deform, const std::vector<vtkIdType>& points)
{
  vtkNew<vtkDoubleArray> deformed;
  deform->GetDeformedPoints(deformed);
  double sum = 0;
  for (vtkIdType i : points)
  {
    sum += deformed->GetComponent(i, 2);
  }
  return sum;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: %s input.off\n", argv[0]);
    return 2;
  }
  FandiskScene scene;
  if (!scene.open(argv[1]))
  {
    return 1;
  }
  const double* b = scene.bounds;
  const double height = scene.height;
  vtkPolyData* input = scene.reader->GetOutput();
  vtkConstraintRegion *fixed = scene.fixed, *handle = scene.handle;
  // the handle rotated about the bottom's -x edge, so that a tilt moves the top's centroid (about
  // its own centroid, a rotation would leave J unchanged)
  handle->UseCentroidOff();
  handle->SetCenter(b[0], 0.5 * (b[2] + b[3]), b[4]);
  const double p[2] = { 0.5, 5.0 }; // the design point: lifted by 5% of the height, tilted by 5 degrees
  setDesign(handle, height, p);

  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputConnection(scene.reader->GetOutputPort());
  deform->AddRegionConnection(fixed->GetOutputPort());
  deform->AddRegionConnection(handle->GetOutputPort());
  deform->ComputeSensitivitiesOn();
  deform->Update();
  vtkPolyData* output = vtkPolyData::SafeDownCast(deform->GetOutput());
  if (output->GetFieldData()->GetAbstractArray("DeformationError"))
  {
    return 1;
  }

  // The handle's points (the Constraint Region's rule: Region(x) <= 0) and dJ/dX on them.
  std::vector<vtkIdType> handlePoints;
  vtkNew<vtkDoubleArray> dJdX;
  dJdX->SetNumberOfComponents(3);
  dJdX->SetNumberOfTuples(input->GetNumberOfPoints());
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    const bool inHandle = scene.top->FunctionValue(input->GetPoint(i)) <= 0;
    dJdX->SetTuple3(i, 0, 0, inHandle ? 1 : 0);
    if (inHandle)
    {
      handlePoints.push_back(i);
    }
  }

  // Reverse mode: dJ/dp for every variable at once.
  vtkNew<vtkDoubleArray> reverse;
  if (!deform->ComputeObjectiveSensitivity(dJdX, reverse))
  {
    std::fprintf(stderr, "%s\n", deform->GetSensitivityError());
    return 1;
  }

  // Forward mode (the dX/d<p> arrays) and the central difference (J(p + h) - J(p - h)) / 2h, per variable.
  const char* names[2] = { "lift", "tilt" };
  const double steps[2] = { 1e-4, 1e-2 }; // small against p, large against the rounding of J
  double forward[2], difference[2];
  for (int v = 0; v < 2; ++v)
  {
    vtkDataArray* dXdp = output->GetPointData()->GetArray(("dX/d" + std::string(names[v])).c_str());
    forward[v] = 0;
    for (vtkIdType i : handlePoints)
    {
      forward[v] += dXdp->GetComponent(i, 2);
    }
  }
  for (int v = 0; v < 2; ++v)
  {
    double plus[2] = { p[0], p[1] }, minus[2] = { p[0], p[1] };
    plus[v] += steps[v];
    minus[v] -= steps[v];
    setDesign(handle, height, plus);
    deform->Update();
    const double up = objective(deform, handlePoints);
    setDesign(handle, height, minus);
    deform->Update();
    difference[v] = (up - objective(deform, handlePoints)) / (2 * steps[v]);
  }

  // Bounds. Reverse and forward mode are two exact evaluations of the same derivative (one linear
  // system solved backwards, once forwards) and differ by rounding only: 1e-9 relative. The
  // central difference has the truncation error h^2/6 |J'''| / |J'|: zero for lift (the
  // deformation is linear in the prescribed displacements, and those in lift), (h pi/180)^2/6 =
  // 5e-9 for tilt (sines and cosines of the angle); and the rounding error of J over 2h (1e-11
  // here): 1e-6 relative. A tilt step of 1 degree (truncation 5e-5) would exceed it.
  const double exactBound = 1e-9, differenceBound = 1e-6;
  std::printf("fandisk: %lld points, %zu in the handle; J = sum of z over the handle; p = (lift %g, tilt %g deg)\n",
    static_cast<long long>(input->GetNumberOfPoints()), handlePoints.size(), p[0], p[1]);
  std::printf("%-6s %22s %22s %22s %12s %12s\n", "dJ/dp", "reverse", "forward", "central difference", "|fwd-rev|", "|FD-rev|");
  bool agree = true;
  // reverse holds dJ/dp in the order of the field data DesignVariableNames
  auto columns = vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray("DesignVariableNames"));
  for (int v = 0; v < 2; ++v)
  {
    const double r = reverse->GetValue(columns->LookupValue(names[v])), scale = std::max(std::abs(r), 1e-300);
    const double exactError = std::abs(forward[v] - r) / scale, differenceError = std::abs(difference[v] - r) / scale;
    std::printf("%-6s %22.15g %22.15g %22.15g %12.2e %12.2e\n", names[v], r, forward[v], difference[v], exactError, differenceError);
    agree = agree && exactError <= exactBound && differenceError <= differenceBound;
  }
  std::printf("relative bounds: forward vs reverse %g (rounding), central difference vs reverse %g (truncation + rounding): %s\n",
    exactBound, differenceBound, agree ? "agree" : "DISAGREE");
  return agree ? 0 : 1;
}
