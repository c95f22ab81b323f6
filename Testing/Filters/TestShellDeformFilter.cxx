// vtkShellDeformFilter, the mesh-based ground truth (section 3), end to end: the plane of Fig. 1,
// the shared cached set-up, and input it cannot deform.
#include "../TestHarness.h"
#include "FilterTestUtilities.h"

#include <vtkPoints.h>

#include <cmath>

namespace
{
using ShellScene = FigureScene<vtkShellDeformFilter>;
}

TEST(StretchingIsLinearBetweenTheStrips)
{
  // Pure stretching with free long sides: the harmonic height is linear in x between the strips.
  vtkSmartPointer<vtkPolyData> plane = figurePlane();
  ShellScene scene(plane);
  scene.deform->SetStretchWeight(1);
  scene.deform->SetBendWeight(0);
  scene.deform->Update();
  auto* out = vtkPolyData::SafeDownCast(scene.deform->GetOutput());
  // the strips' innermost vertex columns: x = 3/32 and 29/32
  const double a = 3.0 / 32, b = 29.0 / 32;
  double error = 0;
  for (vtkIdType i = 0; i < plane->GetNumberOfPoints(); ++i)
  {
    const double x = plane->GetPoint(i)[0];
    const double expected = Lift * (x - a) / (b - a);
    if (x > a && x < b)
      error = std::max(error, std::abs(out->GetPoint(i)[2] - expected));
  }
  std::printf("largest deviation from the linear profile: %.3g of the lift; handle residual %.3g\n", error / Lift,
    fieldValue(out, "HandleResidual"));
  CHECK(error < 1e-4 * Lift);
  CHECK(fieldValue(out, "NumberOfSamples") == 1089);
}

TEST(BendingMeetsTheTargetsSmoothly)
{
  vtkSmartPointer<vtkPolyData> plane = figurePlane();
  double roughness[2];
  for (int stretch = 0; stretch < 2; ++stretch)
  {
    ShellScene scene(plane);
    scene.deform->SetStretchWeight(stretch);
    scene.deform->SetBendWeight(1 - stretch);
    scene.deform->Update();
    auto* out = vtkPolyData::SafeDownCast(scene.deform->GetOutput());
    const double fixedError = targetError(plane, out, FixedBox, 0.0).max, handleError = targetError(plane, out, HandleBox, Lift).max;
    roughness[stretch] = profileRoughness(out);
    std::printf("%s: fixed error %.3g, handle error %.3g, roughness %.3g\n", stretch ? "stretching" : "bending", fixedError, handleError,
      roughness[stretch]);
    CHECK(fixedError <= 0.01 * Lift && handleError <= 0.01 * Lift);
  }
  CHECK(roughness[0] < 0.5 * roughness[1]);
}

TEST(HandleMotionReusesTheSetUp)
{
  vtkSmartPointer<vtkPolyData> plane = figurePlane();
  ShellScene scene(plane);
  scene.deform->Update();
  scene.handle->SetTranslation(0, 0, 2 * Lift);
  scene.deform->Update();
  auto* out = vtkPolyData::SafeDownCast(scene.deform->GetOutput());
  CHECK(scene.deform->GetNumberOfSamplings() == 1 && scene.deform->GetNumberOfFactorizations() == 1);
  CHECK(scene.deform->GetNumberOfSolves() == 2);
  CHECK(targetError(plane, out, HandleBox, 2 * Lift).max <= 0.01 * Lift);
}

TEST(VolumeMeshIsRejected)
{
  // Interior points of a tetrahedral mesh lie on no surface triangle: the shell cannot move them.
  vtkSmartPointer<vtkUnstructuredGrid> box = tetrahedralBox(4);
  ShellScene scene(box);
  auto messages = MessageCollector::watch(scene.deform);
  scene.deform->Update();
  CHECK(messages->errorContains("triangle surfaces only"));
  auto* out = vtkPointSet::SafeDownCast(scene.deform->GetOutputDataObject(0));
  CHECK(out && out->GetNumberOfPoints() == box->GetNumberOfPoints());
  bool unchanged = true;
  for (vtkIdType i = 0; i < box->GetNumberOfPoints(); ++i)
    for (int d = 0; d < 3; ++d)
      unchanged = unchanged && out->GetPoint(i)[d] == box->GetPoint(i)[d];
  CHECK(unchanged);
}

TEST_MAIN
