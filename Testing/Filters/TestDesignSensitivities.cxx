// Design variables and their exact sensitivities (issue 29): dX/dp against central finite
// differences of the filter's own output (GetDeformedPoints: x + d(x) in double precision),
// forward against reverse mode, and bad input.
#include "../TestHarness.h"
#include "FilterTestUtilities.h"

#include "Common/CoreTypes.h"

#include <vtkBox.h>
#include <vtkCellArray.h>
#include <vtkCompositeDataIterator.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkMath.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPlaneSource.h>
#include <vtkStringArray.h>
#include <vtkTransform.h>
#include <vtkTransformFilter.h>

#include <map>
#include <functional>
#include <random>

namespace
{
struct Variable
{
  std::string name;
  int kind; // 0 Translate, 1 Rotate, 2 Scale
  std::vector<std::pair<vtkConstraintRegion*, mlsdeform::Vec3>> regions;
  double value, lower, upper;
  double step; // of the central difference (see the checks' bounds)
};

// The variables onto their regions (each region's list rebuilt in the variables' order).
void apply(const std::vector<Variable>& variables)
{
  std::map<vtkConstraintRegion*, bool> cleared;
  for (const Variable& v : variables)
    for (const auto& [region, axis] : v.regions)
      if (!cleared[region])
      {
        region->RemoveAllDesignVariables();
        cleared[region] = true;
      }
  for (const Variable& v : variables)
    for (const auto& [region, axis] : v.regions)
      region->AddDesignVariable(v.name.c_str(), v.kind, axis.x(), axis.y(), axis.z(), v.value, v.lower, v.upper);
}

// The point sets of a dataset or composite, in output order (a composite iterator's).
std::vector<vtkPointSet*> leaves(vtkDataObject* data)
{
  std::vector<vtkPointSet*> sets;
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it = vtkSmartPointer<vtkCompositeDataIterator>::Take(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
      if (auto* set = vtkPointSet::SafeDownCast(it->GetCurrentDataObject()))
        sets.push_back(set);
  }
  else if (auto* set = vtkPointSet::SafeDownCast(data))
    sets.push_back(set);
  return sets;
}

std::vector<double> deformedPoints(vtkMLSDeformFilter* deform)
{
  deform->Update();
  vtkNew<vtkDoubleArray> X;
  CHECK(deform->GetDeformedPoints(X));
  return std::vector<double>(X->GetPointer(0), X->GetPointer(0) + 3 * X->GetNumberOfTuples());
}

// The filter's column of a variable (field data DesignVariableNames).
int column(vtkMLSDeformFilter* deform, const std::string& name)
{
  auto* names = vtkStringArray::SafeDownCast(deform->GetOutputDataObject(0)->GetFieldData()->GetAbstractArray("DesignVariableNames"));
  for (vtkIdType i = 0; names && i < names->GetNumberOfValues(); ++i)
    if (names->GetValue(i) == name)
      return static_cast<int>(i);
  return -1;
}

std::vector<double> forward(vtkMLSDeformFilter* deform, int variable, int count)
{
  vtkNew<vtkDoubleArray> seeds, dX;
  for (int v = 0; v < count; ++v)
    seeds->InsertNextValue(v == variable ? 1.0 : 0.0);
  CHECK(deform->ComputeSensitivityProduct(seeds, dX));
  return std::vector<double>(dX->GetPointer(0), dX->GetPointer(0) + 3 * dX->GetNumberOfTuples());
}

double largest(const std::vector<double>& a)
{
  double m = 0;
  for (double x : a)
    m = std::max(m, std::abs(x));
  return m;
}

// Every variable's dX/dp against the central difference of the output, relative to max |dX/dp|
// (at most bound), the output arrays dX/d<name> against the forward product (the same
// computation: equal), and reverse mode against forward mode for a random dJ/dX.
void checkSensitivities(vtkMLSDeformFilter* deform, std::vector<Variable> variables, double bound)
{
  apply(variables);
  deform->ComputeSensitivitiesOn();
  const std::vector<double> X = deformedPoints(deform);
  CHECK(deform->GetErrorCode() == vtkErrorCode::NoError);
  std::printf("constraint iterations %g\n", fieldValue(deform->GetOutputDataObject(0), "ConstraintIterations"));
  const int m = static_cast<int>(variables.size());
  std::vector<std::vector<double>> exact(m);
  for (int v = 0; v < m; ++v)
  {
    Variable& var = variables[v];
    deform->Update(); // the sensitivity methods differentiate the last update
    const int c = column(deform, var.name);
    CHECK(c >= 0);
    exact[v] = forward(deform, c, m);
    // the output's arrays over its blocks (in output order) equal the forward product
    std::vector<double> arrays;
    for (vtkPointSet* set : leaves(deform->GetOutputDataObject(0)))
    {
      vtkDataArray* a = set->GetPointData()->GetArray(("dX/d" + var.name).c_str());
      CHECK(a && a->GetNumberOfComponents() == 3);
      for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i)
        for (int k = 0; k < 3; ++k)
          arrays.push_back(a->GetComponent(i, k));
    }
    CHECK(arrays == exact[v]);
    const double p = var.value;
    var.value = p + var.step;
    apply(variables);
    const std::vector<double> plus = deformedPoints(deform);
    var.value = p - var.step;
    apply(variables);
    const std::vector<double> minus = deformedPoints(deform);
    var.value = p;
    apply(variables);
    double difference = 0;
    for (std::size_t i = 0; i < X.size(); ++i)
      difference = std::max(difference, std::abs((plus[i] - minus[i]) / (2 * var.step) - exact[v][i]));
    const double scale = largest(exact[v]);
    std::printf("%-8s max |dX/dp| %.4g, max |FD - exact| %.3g, relative %.3g (bound %g)\n", var.name.c_str(), scale, difference,
      difference / scale, bound);
    CHECK(scale > 0);
    CHECK(difference <= bound * scale);
  }
  deformedPoints(deform); // the session at the variables' values again
  // reverse mode: dJ/dp = sum_i g_i . dX_i/dp for a random g, against the forward arrays; the two
  // sum the same products in other orders: round-off, a few eps of sum |g_i . dX_i/dp|
  std::mt19937 random(29);
  std::normal_distribution<double> normal;
  vtkNew<vtkDoubleArray> g;
  g->SetNumberOfComponents(3);
  g->SetNumberOfTuples(static_cast<vtkIdType>(X.size() / 3));
  for (std::size_t i = 0; i < X.size(); ++i)
    g->SetValue(static_cast<vtkIdType>(i), normal(random));
  vtkNew<vtkDoubleArray> dJdp;
  CHECK(deform->ComputeObjectiveSensitivity(g, dJdp));
  CHECK(dJdp->GetNumberOfTuples() == m);
  for (int v = 0; v < m; ++v)
  {
    double sum = 0, magnitude = 0;
    for (std::size_t i = 0; i < X.size(); ++i)
    {
      sum += g->GetValue(static_cast<vtkIdType>(i)) * exact[v][i];
      magnitude += std::abs(g->GetValue(static_cast<vtkIdType>(i)) * exact[v][i]);
    }
    const double reverse = dJdp->GetValue(column(deform, variables[v].name));
    std::printf("%-8s dJ/dp reverse %.15g, forward %.15g\n", variables[v].name.c_str(), reverse, sum);
    CHECK_NEAR(reverse, sum, 1e-12 * magnitude);
  }
}

// The box [0,2] x [0,1] x [0,1] as tetrahedra and, as a second block, its surface.
vtkSmartPointer<vtkMultiBlockDataSet> boxAndSurface(int n)
{
  vtkSmartPointer<vtkUnstructuredGrid> volume = tetrahedralBox(n);
  vtkNew<vtkDataSetSurfaceFilter> surface;
  surface->SetInputData(volume);
  surface->Update();
  auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  blocks->SetBlock(0, volume);
  blocks->SetBlock(1, surface->GetOutput());
  return blocks;
}

vtkSmartPointer<vtkConstraintRegion> region(vtkAlgorithmOutput* input, int role, std::initializer_list<double> bounds)
{
  return boxRegion(input, role, std::vector<double>(bounds).data());
}
}

// Bounds without iterative constraints: the deformation is linear in a translation and a scale
// variable, so their central difference is exact up to the output's round-off (about 1e-14 of
// the model over a step of 1e-3: 1e-11); a rotation's truncation error is (h pi/180)^2 / 6 =
// 5e-9 relative for h = 0.01 degrees. The bound 1e-6 holds with room.
constexpr double LinearBound = 1e-6;

TEST(TranslationRotationScaleOnSurfaceAndVolume)
{
  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(boxAndSurface(6));
  auto fixed = region(source->GetOutputPort(), vtkConstraintRegion::Fixed, { -0.01, 0.01, -0.01, 1.01, -0.01, 1.01 });
  auto handle = region(source->GetOutputPort(), vtkConstraintRegion::Handle, { 1.49, 2.01, -0.01, 1.01, -0.01, 1.01 });
  handle->SetRotation(5, 0, 10); // a typed motion under the variables
  handle->SetScale(1.1, 1, 1);
  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputConnection(source->GetOutputPort());
  deform->AddRegionConnection(fixed->GetOutputPort());
  deform->AddRegionConnection(handle->GetOutputPort());
  deform->SetNumberOfSamples(200);
  checkSensitivities(deform,
    { { "lift", 0, { { handle, { 0, 0, 1 } } }, 0.05, -0.2, 0.2, 1e-3 }, { "twist", 1, { { handle, { 1, 0, 0 } } }, 4, -10, 10, 1e-2 },
      { "turn", 1, { { handle, { 0, 0, 2 } } }, -1, -10, 10, 1e-2 }, { "stretch", 2, { { handle, { 1, 0, 0 } } }, 0.1, -0.5, 0.5, 1e-3 } },
    LinearBound);
  CHECK(std::string(vtkStringArray::SafeDownCast(deform->GetOutputDataObject(0)->GetFieldData()->GetAbstractArray("SensitivityMethod"))
                      ->GetValue(0))
          .find("exact") == 0);
}

TEST(ZeroValuesLeaveTheTypedMotion)
{
  // p = 0 adds exactly nothing: the output equals the one without design variables bitwise
  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(tetrahedralBox(4));
  auto fixed = region(source->GetOutputPort(), vtkConstraintRegion::Fixed, { -0.01, 0.01, -0.01, 1.01, -0.01, 1.01 });
  auto handle = region(source->GetOutputPort(), vtkConstraintRegion::Handle, { 1.49, 2.01, -0.01, 1.01, -0.01, 1.01 });
  handle->SetTranslation(0, 0, 0.2);
  handle->SetRotation(0, 10, 0);
  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputConnection(source->GetOutputPort());
  deform->AddRegionConnection(fixed->GetOutputPort());
  deform->AddRegionConnection(handle->GetOutputPort());
  deform->SetNumberOfSamples(100);
  const std::vector<double> typed = deformedPoints(deform);
  handle->AddDesignVariable("a", 0, 1, 0, 0, 0, -1, 1);
  handle->AddDesignVariable("b", 1, 0, 1, 1, 0, -1, 1);
  handle->AddDesignVariable("c", 2, 0, 0, 1, 0, -1, 1);
  CHECK(deformedPoints(deform) == typed);
  CHECK(deform->GetNumberOfSamplings() == 1); // the variables keep the set-up
}

TEST(VariableOnTwoRegions)
{
  // one variable spreads a pair of handles apart (opposite axes): its derivative moves the left
  // handle by -y and the right one by +y (within the penalty's target residual)
  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(tetrahedralBox(6));
  auto left = region(source->GetOutputPort(), vtkConstraintRegion::Handle, { -0.01, 0.34, -0.01, 1.01, -0.01, 1.01 });
  auto right = region(source->GetOutputPort(), vtkConstraintRegion::Handle, { 1.66, 2.01, -0.01, 1.01, -0.01, 1.01 });
  auto middle = region(source->GetOutputPort(), vtkConstraintRegion::Fixed, { 0.9, 1.1, -0.01, 1.01, -0.01, 1.01 });
  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputConnection(source->GetOutputPort());
  for (auto* r : { left.Get(), right.Get(), middle.Get() })
    deform->AddRegionConnection(r->GetOutputPort());
  deform->SetNumberOfSamples(200);
  checkSensitivities(deform, { { "spread", 0, { { left, { 0, -1, 0 } }, { right, { 0, 1, 0 } } }, 0.02, 0, 0.1, 1e-3 } }, LinearBound);
  const std::vector<double> dX = forward(deform, 0, 1);
  vtkPointSet* input = vtkPointSet::SafeDownCast(source->GetOutputDataObject(0));
  double leftY = 0, rightY = 0;
  int leftCount = 0, rightCount = 0;
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    const double x = input->GetPoint(i)[0];
    if (x < 0.34)
      leftY += dX[3 * i + 1], ++leftCount;
    if (x > 1.66)
      rightY += dX[3 * i + 1], ++rightCount;
  }
  // the handles meet their targets within 1% at the default weights (issue 12's target)
  CHECK_NEAR(leftY / leftCount, -1, 0.01);
  CHECK_NEAR(rightY / rightCount, 1, 0.01);
}

// The channel of SlipPlanesLetABodySlide (TestMLSDeformFilter.cxx), tilted or not, with a body
// on its slipping ground that slides (x) and turns about the ground's normal.
void checkSlidingBody(double tilt, double bound)
{
  vtkNew<vtkTransform> rotation;
  rotation->RotateWXYZ(tilt, 1, 2, 3);
  vtkNew<vtkTransformFilter> tilted;
  tilted->SetInputData(tetrahedralBox(6));
  tilted->SetTransform(rotation);
  auto in = [&](int role, std::initializer_list<double> bounds) {
    auto r = region(tilted->GetOutputPort(), role, bounds);
    r->GetRegion()->SetTransform(rotation->GetLinearInverse());
    return r;
  };
  auto body = in(vtkConstraintRegion::Handle, { 0.8, 1.2, 0.3, 0.7, -0.01, 0.25 });
  auto inlet = in(vtkConstraintRegion::Fixed, { -0.01, 0.01, -0.01, 1.01, -0.01, 1.01 });
  auto outlet = in(vtkConstraintRegion::Fixed, { 1.99, 2.01, -0.01, 1.01, -0.01, 1.01 });
  auto ground = in(vtkConstraintRegion::Slip, { -0.01, 2.01, -0.01, 1.01, -0.01, 0.01 });
  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputConnection(tilted->GetOutputPort());
  for (auto* r : { body.Get(), inlet.Get(), outlet.Get(), ground.Get() })
    deform->AddRegionConnection(r->GetOutputPort());
  deform->SetNumberOfSamples(200);
  deform->SetTolerance(1e-12);
  deform->SetMaxIterations(100000);
  double along[3] = { 1, 0, 0 }, normal[3] = { 0, 0, 1 };
  rotation->TransformVector(along, along);
  rotation->TransformNormal(normal, normal);
  checkSensitivities(deform,
    { { "slide", 0, { { body, { along[0], along[1], along[2] } } }, 0.05, -0.2, 0.2, 1e-3 },
      { "yaw", 1, { { body, { normal[0], normal[1], normal[2] } } }, 3, -10, 10, 1e-2 } },
    bound);
}

TEST(ExactSlipPlane)
{
  checkSlidingBody(0, LinearBound); // normal to z: exact, no iteration
}

// With the constraint iteration: it stops within Tolerance (1e-12) of the model's length of its
// fixed point, which the central difference divides by 2h (1e-9 relative for h = 1e-3 on
// |dX/dp| ~ 1); the derivative's own error is GMRES's 1e-10 and the projections' central
// differences' (LinearizedFixedPoint.h: truncation 1e-8 for shapes the size of these scenes, the
// cylinder fit's axis resolution 1e-6). With exact constraints (the default) the intersection's
// central differences add its tolerance over the step, 1e-11 / 1e-4 = 1e-7
// (DeformationSession.cxx). The bound 1e-4 holds with room.
constexpr double IterativeBound = 1e-4;

// The constraint holds exactly in the output whose derivatives were checked (issue 31): the
// alternating projections' tolerance, 1e-11 of the diagonal, below the 1e-9.
void checkConstraintExact(vtkMLSDeformFilter* deform)
{
  const double residual = fieldValue(deform->GetOutputDataObject(0), "ConstraintResidual");
  std::printf("constraint residual %.3g of the diagonal\n", residual);
  CHECK(residual >= 0 && residual <= 1e-9);
}

TEST(TiltedSlipPlane)
{
  checkSlidingBody(30, IterativeBound);
}

// A box twisted and lifted at one end with constraint regions made by constraints(its output
// port): the derivatives against central differences, and the constraints exact. Returns the
// deformation.
vtkSmartPointer<vtkMLSDeformFilter> checkTwistedBox(const std::function<std::vector<vtkSmartPointer<vtkConstraintRegion>>(vtkAlgorithmOutput*)>& constraints)
{
  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(tetrahedralBox(6));
  auto fixed = region(source->GetOutputPort(), vtkConstraintRegion::Fixed, { -0.01, 0.01, -0.01, 1.01, -0.01, 1.01 });
  auto handle = region(source->GetOutputPort(), vtkConstraintRegion::Handle, { 1.82, 2.01, -0.01, 1.01, -0.01, 1.01 });
  auto deform = vtkSmartPointer<vtkMLSDeformFilter>::New();
  deform->SetInputConnection(source->GetOutputPort());
  std::vector<vtkSmartPointer<vtkConstraintRegion>> regions = constraints(source->GetOutputPort());
  regions.insert(regions.begin(), { fixed, handle });
  for (auto& r : regions)
    deform->AddRegionConnection(r->GetOutputPort());
  deform->SetNumberOfSamples(200);
  deform->SetTolerance(1e-12);
  deform->SetMaxIterations(100000);
  checkSensitivities(deform,
    { { "lift", 0, { { handle, { 0, 0, 1 } } }, 0.1, -0.3, 0.3, 1e-3 }, { "twist", 1, { { handle, { 1, 0, 0 } } }, 10, -20, 20, 1e-2 } },
    IterativeBound);
  checkConstraintExact(deform);
  CHECK(std::string(vtkStringArray::SafeDownCast(deform->GetOutputDataObject(0)->GetFieldData()->GetAbstractArray("SensitivityMethod"))
                      ->GetValue(0))
          .find("implicit differentiation") != std::string::npos);
  return deform;
}

TEST(PlanarityConstraint)
{
  // a planar patch on the front face
  checkTwistedBox([](vtkAlgorithmOutput* box) {
    return std::vector<vtkSmartPointer<vtkConstraintRegion>>{ region(box, vtkConstraintRegion::Planarity,
      { 0.6, 1.4, -0.01, 0.01, -0.01, 1.01 }) };
  });
}

TEST(DistanceConstraint)
{
  // two patches of the front face keep the distance of their centroids
  checkTwistedBox([](vtkAlgorithmOutput* box) {
    return std::vector<vtkSmartPointer<vtkConstraintRegion>>{ region(box, vtkConstraintRegion::Distance, { 0.3, 0.7, -0.01, 0.01, -0.01, 1.01 }),
      region(box, vtkConstraintRegion::Distance, { 1.3, 1.7, -0.01, 0.01, -0.01, 1.01 }) };
  });
}

TEST(OffsetConstraint)
{
  // the top face's middle keeps 0.35 from a plane above it (0.4 at rest; the lift pushes the
  // part near the handle nearer: active there, not at the other end)
  const auto deform = checkTwistedBox([](vtkAlgorithmOutput* box) {
    auto skin = region(box, vtkConstraintRegion::Offset, { 0.9, 1.7, -0.01, 1.01, 0.99, 1.01 });
    vtkNew<vtkPlaneSource> reference;
    reference->SetOrigin(-1, -1, 1.4);
    reference->SetPoint1(3, -1, 1.4);
    reference->SetPoint2(-1, 2, 1.4);
    reference->Update();
    skin->SetInputData(1, reference->GetOutput()); // held by the region (a port would not hold its source)
    skin->SetMinimumDistance(0.35);
    return std::vector<vtkSmartPointer<vtkConstraintRegion>>{ skin };
  });
  // active: the skin's highest point sits on the bound
  auto* out = vtkPointSet::SafeDownCast(deform->GetOutputDataObject(0));
  double highest = -1;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double x[3];
    out->GetPoint(i, x);
    if (x[0] > 0.85 && x[0] < 1.75 && x[2] > 0.9)
      highest = std::max(highest, x[2]);
  }
  std::printf("the skin's least distance from the plane: %.9f (bound 0.35)\n", 1.4 - highest);
  CHECK(std::abs(1.4 - highest - 0.35) <= 1e-6); // the output's float points
}

// A tube of radius 0.5 about the z axis, height 2, as triangles (rings every 0.1, 32 around).
vtkSmartPointer<vtkPolyData> tube()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  const int around = 32, rings = 21;
  for (int r = 0; r < rings; ++r)
    for (int a = 0; a < around; ++a)
      points->InsertNextPoint(0.5 * std::cos(2 * vtkMath::Pi() * a / around), 0.5 * std::sin(2 * vtkMath::Pi() * a / around), 0.1 * r);
  for (int r = 0; r + 1 < rings; ++r)
    for (int a = 0; a < around; ++a)
    {
      const vtkIdType p = r * around + a, q = r * around + (a + 1) % around;
      const vtkIdType t1[3] = { p, q, q + around }, t2[3] = { p, q + around, p + around };
      triangles->InsertNextCell(3, t1);
      triangles->InsertNextCell(3, t2);
    }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(triangles);
  return mesh;
}

// The tube bent sideways at its top, a band (Cylinder) or a ring (Circularity) in the middle kept
// by its constraint: the sensitivities and the constraint exact.
void checkTubeConstraint(int role, double halfHeight)
{
  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(tube());
  auto fixed = region(source->GetOutputPort(), vtkConstraintRegion::Fixed, { -1, 1, -1, 1, -0.01, 0.01 });
  auto handle = region(source->GetOutputPort(), vtkConstraintRegion::Handle, { -1, 1, -1, 1, 1.99, 2.01 });
  auto kept = region(source->GetOutputPort(), role, { -1, 1, -1, 1, 1 - halfHeight, 1 + halfHeight });
  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputConnection(source->GetOutputPort());
  for (auto* r : { fixed.Get(), handle.Get(), kept.Get() })
    deform->AddRegionConnection(r->GetOutputPort());
  deform->SetNumberOfSamples(200);
  deform->SetTolerance(1e-12);
  deform->SetMaxIterations(100000);
  checkSensitivities(deform,
    { { "sway", 0, { { handle, { 1, 0, 0 } } }, 0.1, -0.3, 0.3, 1e-3 }, { "flare", 2, { { handle, { 1, 1, 0 } } }, 0.1, -0.3, 0.3, 1e-3 } },
    IterativeBound);
  checkConstraintExact(deform);
}

TEST(CylinderConstraint)
{
  checkTubeConstraint(vtkConstraintRegion::Cylinder, 0.21); // five rings
}

TEST(CircularityConstraint)
{
  checkTubeConstraint(vtkConstraintRegion::Circularity, 0.01); // one ring
}

// A deformation of the box with a handle; regions and filter for the bad-input tests.
struct BadInputScene
{
  vtkNew<vtkTrivialProducer> source;
  vtkSmartPointer<vtkConstraintRegion> fixed, handle;
  vtkNew<vtkMLSDeformFilter> deform;
  BadInputScene()
  {
    source->SetOutput(tetrahedralBox(4));
    fixed = region(source->GetOutputPort(), vtkConstraintRegion::Fixed, { -0.01, 0.01, -0.01, 1.01, -0.01, 1.01 });
    handle = region(source->GetOutputPort(), vtkConstraintRegion::Handle, { 1.49, 2.01, -0.01, 1.01, -0.01, 1.01 });
    deform->SetInputConnection(source->GetOutputPort());
    deform->AddRegionConnection(fixed->GetOutputPort());
    deform->AddRegionConnection(handle->GetOutputPort());
    deform->SetNumberOfSamples(100);
  }
};

// A 2D case extruded along z (ExtrusionAxis; an OpenFOAM case with empty front and back planes,
// here the box with its z = 0 and z = 1 planes as Slip regions): every point moves by the
// displacement of its projection onto the mid-plane, without a z component, so points with the
// same x and y move alike to the last bit, and their derivatives too. The planes' Slip regions
// are implied (not iterated on: the deformation stays linear, its sensitivities exact).
TEST(ExtrudedCaseStaysTwoDimensional)
{
  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(boxAndSurface(5));
  auto fixed = region(source->GetOutputPort(), vtkConstraintRegion::Fixed, { -0.01, 0.01, -0.01, 1.01, -0.01, 1.01 });
  auto handle = region(source->GetOutputPort(), vtkConstraintRegion::Handle, { 1.59, 2.01, -0.01, 1.01, -0.01, 1.01 });
  auto front = region(source->GetOutputPort(), vtkConstraintRegion::Slip, { -0.01, 2.01, -0.01, 1.01, -0.01, 0.01 });
  auto back = region(source->GetOutputPort(), vtkConstraintRegion::Slip, { -0.01, 2.01, -0.01, 1.01, 0.99, 1.01 });
  handle->SetRotation(0, 0, 8);
  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputConnection(source->GetOutputPort());
  for (auto* r : { fixed.Get(), handle.Get(), front.Get(), back.Get() })
    deform->AddRegionConnection(r->GetOutputPort());
  deform->SetNumberOfSamples(200);
  deform->SetExtrusionAxis(vtkMLSDeformFilter::ExtrudedZ);
  const std::vector<Variable> variables = { { "lift", 0, { { handle, { 0, 1, 0.3 } } }, 0.05, -0.2, 0.2, 1e-3 },
    { "turn", 1, { { handle, { 0, 0.2, 1 } } }, -2, -10, 10, 1e-2 } };
  checkSensitivities(deform, variables, LinearBound);
  CHECK(std::string(vtkStringArray::SafeDownCast(deform->GetOutputDataObject(0)->GetFieldData()->GetAbstractArray("SensitivityMethod"))
                      ->GetValue(0))
          .find("exact") == 0);
  // the axes' z parts (0.3, and the turn's tilt) have no effect: x and y alone decide
  const std::vector<double> X = deformedPoints(deform);
  std::vector<std::vector<double>> derivatives;
  for (int v = 0; v < 2; ++v)
    derivatives.push_back(forward(deform, v, 2));
  std::vector<double> input;
  for (vtkPointSet* set : leaves(source->GetOutputDataObject(0)))
    for (vtkIdType i = 0; i < set->GetNumberOfPoints(); ++i)
      for (int k = 0; k < 3; ++k)
        input.push_back(set->GetPoint(i)[k]);
  std::map<std::pair<double, double>, std::vector<std::size_t>> twins;
  for (std::size_t i = 0; i < input.size() / 3; ++i)
    twins[{ input[3 * i], input[3 * i + 1] }].push_back(i);
  std::size_t pairs = 0, alike = 0, flat = 0;
  for (const auto& [xy, points] : twins)
    for (std::size_t i : points)
    {
      const std::size_t j = points.front();
      flat += X[3 * i + 2] == input[3 * i + 2] && derivatives[0][3 * i + 2] == 0 && derivatives[1][3 * i + 2] == 0;
      if (i == j)
        continue;
      ++pairs;
      bool same = true;
      for (int k = 0; k < 2; ++k)
        same = same && X[3 * i + k] - input[3 * i + k] == X[3 * j + k] - input[3 * j + k] &&
          derivatives[0][3 * i + k] == derivatives[0][3 * j + k] && derivatives[1][3 * i + k] == derivatives[1][3 * j + k];
      alike += same;
    }
  std::printf("extruded: %zu of %zu points keep z, %zu of %zu twins move alike\n", flat, input.size() / 3, alike, pairs);
  CHECK(pairs > 0);
  CHECK(alike == pairs);
  CHECK(flat == input.size() / 3);
  CHECK(fieldValue(deform->GetOutputDataObject(0), "InvertedCells") == 0);
}

TEST(ExtrudedCaseRefusesShapeConstraints)
{
  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(tetrahedralBox(4));
  auto fixed = region(source->GetOutputPort(), vtkConstraintRegion::Fixed, { -0.01, 0.01, -0.01, 1.01, -0.01, 1.01 });
  auto handle = region(source->GetOutputPort(), vtkConstraintRegion::Handle, { 1.49, 2.01, -0.01, 1.01, -0.01, 1.01 });
  auto planar = region(source->GetOutputPort(), vtkConstraintRegion::Planarity, { 0.9, 1.1, -0.01, 1.01, -0.01, 1.01 });
  handle->SetTranslation(0, 0.1, 0);
  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputConnection(source->GetOutputPort());
  for (auto* r : { fixed.Get(), handle.Get(), planar.Get() })
    deform->AddRegionConnection(r->GetOutputPort());
  deform->SetNumberOfSamples(100);
  deform->SetExtrusionAxis(vtkMLSDeformFilter::ExtrudedZ);
  auto messages = MessageCollector::watch(deform);
  deform->Update();
  CHECK(messages->errorContains("Planarity region in a 2D (extruded) deformation"));
  CHECK(deform->GetErrorCode() == vtkErrorCode::UserError);
  deform->SetExtrusionAxis(vtkMLSDeformFilter::NoExtrusion); // the same scene in 3D is fine
  deform->Update();
  CHECK(deform->GetErrorCode() == vtkErrorCode::NoError);
}

TEST(BadDesignVariablesAreReported)
{
  struct Case
  {
    const char* message;
    std::function<void(BadInputScene&)> set;
  };
  const std::vector<Case> cases = {
    { "act on a Handle region's motion", [](BadInputScene& s) { s.fixed->AddDesignVariable("a", 0, 1, 0, 0, 0, -1, 1); } },
    { "non-zero, finite axis", [](BadInputScene& s) { s.handle->AddDesignVariable("a", 0, 0, 0, 0, 0, -1, 1); } },
    { "defined twice", [](BadInputScene& s) {
       s.handle->AddDesignVariable("a", 0, 1, 0, 0, 0, -1, 1);
       s.handle->AddDesignVariable("a", 1, 1, 0, 0, 0, -1, 1);
     } },
    { "lower <= upper", [](BadInputScene& s) { s.handle->AddDesignVariable("a", 0, 1, 0, 0, 0, 1, -1); } },
    { "outside its bounds", [](BadInputScene& s) { s.handle->AddDesignVariable("a", 0, 1, 0, 0, 2, -1, 1); } },
    { "unknown kind", [](BadInputScene& s) { s.handle->AddDesignVariable("a", 4, 1, 0, 0, 0, -1, 1); } },
    { "its axis must be 0 0 0", [](BadInputScene& s) { s.handle->AddDesignVariable("a", 3, 1, 0, 0, 0, -1, 1); } },
    { "has no control point", [](BadInputScene& s) { s.handle->AddDesignVariable("a", 3, 0, 0, 0, 0, -1, 1); } },
    { "not a Local design variable", [](BadInputScene& s) { s.handle->AddControlPoint("b", 0, 0, 0, 0, 0, 0, 0, 0, 0); } },
    { "not finite", [](BadInputScene& s) {
       s.handle->AddDesignVariable("a", 3, 0, 0, 0, 0, -1, 1);
       s.handle->AddControlPoint("a", std::nan(""), 0, 0, 0, 0, 0, 0, 0, 0);
     } },
    { "one variable has one value", [](BadInputScene& s) {
       // the same name on a second handle with another value
       auto second = region(s.source->GetOutputPort(), vtkConstraintRegion::Handle, { 0.9, 1.1, -0.01, 1.01, -0.01, 1.01 });
       s.deform->AddRegionConnection(second->GetOutputPort());
       s.handle->AddDesignVariable("a", 0, 1, 0, 0, 0, -1, 1);
       second->AddDesignVariable("a", 0, 1, 0, 0, 0.5, -1, 1);
       s.deform->Update();
     } },
  };
  for (const Case& c : cases)
  {
    BadInputScene scene;
    auto messages = MessageCollector::watch(scene.deform);
    auto handleMessages = MessageCollector::watch(scene.handle);
    auto fixedMessages = MessageCollector::watch(scene.fixed);
    c.set(scene);
    scene.deform->Update();
    const bool reported = messages->errorContains(c.message) || handleMessages->errorContains(c.message) || fixedMessages->errorContains(c.message);
    std::printf("%s: %s\n", c.message, reported ? "reported" : "NOT reported");
    CHECK(reported);
    CHECK(scene.deform->GetErrorCode() == vtkErrorCode::UserError);
    vtkNew<vtkDoubleArray> X;
    X->InsertNextValue(42);
    CHECK(!scene.deform->GetDeformedPoints(X)); // no successful update: nothing to differentiate
    CHECK(X->GetNumberOfTuples() == 1 && X->GetValue(0) == 42);
  }
}

TEST(BadGradientsChangeNothing)
{
  BadInputScene scene;
  scene.handle->AddDesignVariable("a", 0, 0, 0, 1, 0.1, -1, 1);
  scene.deform->Update();
  const vtkIdType n = vtkPointSet::SafeDownCast(scene.deform->GetOutputDataObject(0))->GetNumberOfPoints();
  auto messages = MessageCollector::watch(scene.deform);
  const auto tryGradient = [&](vtkIdType tuples, int components, double value, const char* message) {
    vtkNew<vtkDoubleArray> g, out;
    g->SetNumberOfComponents(components);
    g->SetNumberOfTuples(tuples);
    g->Fill(value);
    out->InsertNextValue(42);
    CHECK(!scene.deform->ComputeObjectiveSensitivity(g, out));
    CHECK(out->GetNumberOfTuples() == 1 && out->GetValue(0) == 42);
    CHECK(std::string(scene.deform->GetSensitivityError()).find(message) != std::string::npos);
    std::printf("expected error: %s\n", scene.deform->GetSensitivityError());
  };
  tryGradient(n - 1, 3, 1.0, "3 components per output point");
  tryGradient(n, 1, 1.0, "3 components per output point");
  tryGradient(n, 3, std::nan(""), "not finite");
  vtkNew<vtkDoubleArray> seeds, out;
  seeds->InsertNextValue(1);
  seeds->InsertNextValue(2);
  CHECK(!scene.deform->ComputeSensitivityProduct(seeds, out));
  CHECK(messages->errorContains("one seed per design variable"));
  // the input's dJ/dX array by name: a missing one and a NaN fail the update with the message
  scene.deform->SetObjectiveGradientArray("dJdX");
  scene.deform->Update();
  CHECK(messages->errorContains("is no point array of the input"));
  vtkNew<vtkDoubleArray> bad;
  bad->SetName("dJdX");
  bad->SetNumberOfComponents(3);
  bad->SetNumberOfTuples(n);
  bad->Fill(std::nan(""));
  vtkPointSet::SafeDownCast(scene.source->GetOutputDataObject(0))->GetPointData()->AddArray(bad);
  scene.source->Modified();
  scene.deform->Update();
  CHECK(messages->errorContains("not finite"));
  CHECK(scene.deform->GetErrorCode() == vtkErrorCode::UserError);
}

TEST(ObjectiveGradientArrayOfTheInput)
{
  // the pipeline's reverse mode (an input array dJ/dX) equals the method's
  BadInputScene scene;
  scene.handle->AddDesignVariable("a", 0, 0, 0, 1, 0.1, -1, 1);
  scene.handle->AddDesignVariable("b", 1, 0, 1, 0, 2, -5, 5);
  vtkPointSet* input = vtkPointSet::SafeDownCast(scene.source->GetOutputDataObject(0));
  vtkNew<vtkDoubleArray> g;
  g->SetName("dJdX");
  g->SetNumberOfComponents(3);
  g->SetNumberOfTuples(input->GetNumberOfPoints());
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
    g->SetTuple3(i, input->GetPoint(i)[0] > 1.5 ? 1.0 : 0.0, 0.5, input->GetPoint(i)[2]);
  input->GetPointData()->AddArray(g);
  scene.deform->SetObjectiveGradientArray("dJdX");
  scene.deform->Update();
  vtkDataArray* field = scene.deform->GetOutputDataObject(0)->GetFieldData()->GetArray("ObjectiveSensitivity");
  CHECK(field && field->GetNumberOfTuples() == 2);
  vtkNew<vtkDoubleArray> out;
  CHECK(scene.deform->ComputeObjectiveSensitivity(g, out));
  for (vtkIdType v = 0; field && v < 2; ++v)
    CHECK(field->GetTuple1(v) == out->GetValue(v));
}

TEST_MAIN
