// The handle motion (Filters/HandleMotion.h): its matrix, its recovery from a matrix as the box
// widget produces it, the box widget's description of it, and the Constraint Region's
// prescribed displacement.
#include "../TestHarness.h"
#include "Adapters/HandleMotion.h"
#include "vtkConstraintRegion.h"

#include <vtkDataArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTransform.h>

#include <random>

using mlsvtk::HandleMotion;

namespace
{
// Matrix entries are sums of 3 products of values <= ~10 (scales, coordinates): a few ulps of 10.
constexpr double MatrixTolerance = 1e-13;

HandleMotion randomMotion(std::mt19937_64& random)
{
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  HandleMotion m;
  for (int i = 0; i < 3; ++i)
  {
    m.translation[i] = 2 * unit(random);
    m.scale[i] = 1.5 + unit(random); // positive, as the box widget's
  }
  m.rotation[0] = 179 * unit(random);
  m.rotation[1] = 89 * unit(random); // away from the gimbal lock at +-90
  m.rotation[2] = 179 * unit(random);
  return m;
}

double largestDifference(const double a[16], const double b[16])
{
  double d = 0;
  for (int i = 0; i < 16; ++i)
  {
    d = std::max(d, std::abs(a[i] - b[i]));
  }
  return d;
}
}

TEST(MatrixScalesRotatesAndTranslatesAboutThePivot)
{
  // scale 2 along X, then 90 degrees about Z, about the pivot (1, 0, 0), then up by 1:
  // (2, 0, 0) -> pivot + Rz (2 (1, 0, 0)) + (0, 0, 1) = (1, 2, 1)
  HandleMotion m;
  m.scale[0] = 2;
  m.rotation[2] = 90;
  m.translation[2] = 1;
  const double pivot[3] = { 1, 0, 0 };
  double M[16];
  mlsvtk::handleMotionMatrix(m, pivot, M);
  const double x[3] = { 2, 0, 0 };
  const double expected[3] = { 1, 2, 1 };
  for (int i = 0; i < 3; ++i)
  {
    CHECK_NEAR(M[4 * i] * x[0] + M[4 * i + 1] * x[1] + M[4 * i + 2] * x[2] + M[4 * i + 3], expected[i], MatrixTolerance);
  }
  // rotations about X first, then Y: Ry(90) Rx(90) maps Y to X (Rx: Y -> Z, Ry: Z -> X)
  HandleMotion r;
  r.rotation[0] = 90;
  r.rotation[1] = 90;
  const double origin[3] = { 0, 0, 0 };
  mlsvtk::handleMotionMatrix(r, origin, M);
  CHECK_NEAR(M[1], 1, MatrixTolerance);
}

TEST(MotionIsRecoveredFromItsMatrix)
{
  std::mt19937_64 random(7);
  for (int trial = 0; trial < 100; ++trial)
  {
    const HandleMotion m = randomMotion(random);
    const double pivot[3] = { 0.3 * trial, -1, 2 };
    double M[16];
    mlsvtk::handleMotionMatrix(m, pivot, M);
    const HandleMotion back = mlsvtk::handleMotion(M, pivot);
    for (int i = 0; i < 3; ++i)
    {
      // angles from atan2/asin of entries exact to ~1e-16: ~1e-14 degrees; asin near b = 89
      // degrees amplifies by 1/cos b = 57
      CHECK_NEAR(back.rotation[i], m.rotation[i], 1e-11);
      CHECK_NEAR(back.scale[i], m.scale[i], 1e-14 * 4);
      // t = p + A pivot - pivot with |pivot| up to 30: a few ulps of 30
      CHECK_NEAR(back.translation[i], m.translation[i], 1e-13);
    }
  }
  // gimbal lock: the angles are not unique, the map is
  HandleMotion lock;
  lock.rotation[0] = 30;
  lock.rotation[1] = 90;
  lock.rotation[2] = 10;
  const double pivot[3] = { 1, 2, 3 };
  double M[16], again[16];
  mlsvtk::handleMotionMatrix(lock, pivot, M);
  mlsvtk::handleMotionMatrix(mlsvtk::handleMotion(M, pivot), pivot, again);
  CHECK(largestDifference(M, again) < MatrixTolerance);
}

TEST(BoxWidgetTransformGivesTheSameMap)
{
  // vtkPVTransform (the box widget's): translate, rotate about Z, X, then Y, scale
  std::mt19937_64 random(11);
  for (int trial = 0; trial < 100; ++trial)
  {
    const HandleMotion m = randomMotion(random);
    const double pivot[3] = { 1, -0.5 * trial, 0.25 };
    const mlsvtk::BoxTransform box = mlsvtk::boxTransform(m, pivot);
    vtkNew<vtkTransform> widget;
    widget->Translate(box.position);
    widget->RotateZ(box.rotation[2]);
    widget->RotateX(box.rotation[0]);
    widget->RotateY(box.rotation[1]);
    widget->Scale(box.scale);
    double W[16], M[16];
    vtkMatrix4x4::DeepCopy(W, widget->GetMatrix());
    mlsvtk::handleMotionMatrix(m, pivot, M);
    // GetOrientation's angles come from atan2 of the rotation's entries: ~1e-15 relative; the
    // translation column holds |pivot| up to 50
    CHECK(largestDifference(W, M) < 1e-12);
  }
}

TEST(RegionDisplacementFollowsTheMotionAboutTheCentroid)
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(2, 0, 0);
  points->InsertNextPoint(1, 3, 0);
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkConstraintRegion> region;
  region->SetInputData(cloud);
  region->SetSelectionMode(vtkConstraintRegion::AllPoints);
  region->SetTranslation(0.5, 0, 0);
  region->SetRotation(0, 0, 90);
  region->SetScale(2, 1, 1);
  region->Update();
  const double* pivot = region->GetPivot();
  CHECK_NEAR(pivot[0], 1, 1e-15);
  CHECK_NEAR(pivot[1], 1, 1e-15);
  // (2, 0, 0): from the centroid (1, 1, 0) it is (1, -1, 0), scaled (2, -1, 0), rotated (1, 2, 0),
  // so it lands at (1, 1, 0) + (1, 2, 0) + (0.5, 0, 0) = (2.5, 3, 0)
  vtkDataArray* d = region->GetOutput()->GetPointData()->GetArray("PrescribedDisplacement");
  CHECK_NEAR(d->GetComponent(1, 0), 2.5 - 2, 1e-14);
  CHECK_NEAR(d->GetComponent(1, 1), 3 - 0, 1e-14);
  CHECK_NEAR(d->GetComponent(1, 2), 0, 1e-14);
}

TEST_MAIN
