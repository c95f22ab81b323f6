// Section 4: MLS shape functions reproduce linear fields, derivatives are analytic and right,
// coplanar samples are handled by the pseudo-inverse.
#include "MLSBasis.h"
#include "Sampling.h"
#include "ShapeFunctionChecks.h"
#include "TestGeometry.h"
#include "../TestHarness.h"

using namespace mlsdeform;
using namespace testgeometry;

namespace
{
MLSBasis randomBasis(const PointList& centers, const PointList& covered, double cover = 5)
{
  return MLSBasis(centers, coverSupportRadii(centers, { &covered, &centers }, cover));
}

}

TEST(WeightFunction)
{
  CHECK_NEAR(MLSBasis::weight(0.0, 2.0), 1.0, 1e-15);
  CHECK_NEAR(MLSBasis::weight(1.0, 2.0), 0.5, 1e-15);
  CHECK_NEAR(MLSBasis::weight(2.0, 2.0), 0.0, 1e-15);
  CHECK_NEAR(MLSBasis::weight(3.0, 2.0), 0.0, 0.0);
}

TEST(PartitionOfUnityAndLinearReproduction)
{
  const PointList centers = randomPoints(400, Vec3(0, 0, 0), Vec3(1, 2, 1), 1);
  const PointList evaluation = randomPoints(1000, Vec3(0, 0, 0), Vec3(1, 2, 1), 2);
  const MLSBasis basis = randomBasis(centers, evaluation);
  ShapeFunctionValues phi;
  double unity = 0, linear = 0, gradient = 0, laplacian = 0;
  for (const Vec3& x : evaluation)
  {
    basis.evaluate(x, phi, true);
    CHECK(phi.index.size() >= 5);
    double sum = 0, sumLaplacian = 0;
    Vec3 reproduced = Vec3::Zero(), sumGradient = Vec3::Zero(), laplacianOfLinear = Vec3::Zero();
    Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
    for (std::size_t a = 0; a < phi.index.size(); ++a)
    {
      const Vec3& c = centers[phi.index[a]];
      sum += phi.value[a];
      reproduced += phi.value[a] * c;
      sumGradient += phi.gradient[a];
      jacobian += c * phi.gradient[a].transpose();
      sumLaplacian += phi.laplacian[a];
      laplacianOfLinear += phi.laplacian[a] * c;
    }
    unity = std::max(unity, std::abs(sum - 1));
    linear = std::max(linear, (reproduced - x).norm());
    gradient = std::max({ gradient, sumGradient.norm(), (jacobian - Eigen::Matrix3d::Identity()).norm() });
    laplacian = std::max({ laplacian, std::abs(sumLaplacian), laplacianOfLinear.norm() });
  }
  std::printf("max errors: unity %g, linear %g, gradient %g, laplacian %g\n", unity, linear, gradient, laplacian);
  CHECK(unity <= 1e-10);
  CHECK(linear <= 1e-10);
  CHECK(gradient <= 1e-8);  // derivatives of 1 and x: 0 and I
  CHECK(laplacian <= 1e-6); // Laplacians of 1 and x: 0 (entries scale with 1/sigma^2)
}

TEST(DerivativesMatchFiniteDifferences)
{
  const PointList centers = randomPoints(300, Vec3(0, 0, 0), Vec3(1, 1, 1), 3);
  const PointList evaluation = randomPoints(50, Vec3(0.1, 0.1, 0.1), Vec3(0.9, 0.9, 0.9), 4);
  const MLSBasis basis = randomBasis(centers, evaluation);
  // w(r) = 1/2 cos(pi r/sigma) + 1/2 is C1 only at r = sigma: its second derivative jumps there,
  // so finite differences across a support boundary do not approximate the Laplacian.
  const DerivativeErrors e = finiteDifferenceErrors(basis, evaluation, [&](const Vec3& x) {
    for (std::size_t j = 0; j < centers.size(); ++j)
      if (std::abs((x - centers[j]).norm() - basis.supportRadii()[j]) < 1e-3)
        return true;
    return false;
  });
  std::printf("%d points: gradient error %g (scale %g), Laplacian error %g (scale %g)\n", e.compared, e.gradient, e.gradientScale, e.laplacian, e.laplacianScale);
  CHECK(e.compared >= 25);
  CHECK(e.gradient <= 1e-6 * e.gradientScale);
  CHECK(e.laplacian <= 1e-3 * e.laplacianScale);
}

TEST(CoplanarSamples)
{
  // All samples on z = 1: the moment matrix has rank 3 everywhere.
  PointList centers = randomPoints(200, Vec3(0, 0, 1), Vec3(1, 1, 1), 5);
  const PointList inPlane = randomPoints(200, Vec3(0.1, 0.1, 1), Vec3(0.9, 0.9, 1), 6);
  const PointList offPlane = randomPoints(200, Vec3(0.1, 0.1, 0.98), Vec3(0.9, 0.9, 1.02), 7);
  const MLSBasis basis = randomBasis(centers, offPlane);
  ShapeFunctionValues phi;
  double inPlaneError = 0, offPlaneUnity = 0;
  bool finite = true;
  for (const Vec3& x : inPlane)
  {
    basis.evaluate(x, phi, true);
    double sum = 0;
    Vec3 reproduced = Vec3::Zero();
    for (std::size_t a = 0; a < phi.index.size(); ++a)
    {
      sum += phi.value[a];
      reproduced += phi.value[a] * centers[phi.index[a]];
      finite = finite && phi.gradient[a].allFinite() && std::isfinite(phi.laplacian[a]);
    }
    inPlaneError = std::max({ inPlaneError, std::abs(sum - 1), (reproduced - x).norm() });
  }
  for (const Vec3& x : offPlane)
  {
    basis.evaluate(x, phi, true);
    double sum = 0;
    for (std::size_t a = 0; a < phi.index.size(); ++a)
    {
      sum += phi.value[a];
      finite = finite && std::isfinite(phi.value[a]) && phi.gradient[a].allFinite() && std::isfinite(phi.laplacian[a]);
    }
    offPlaneUnity = std::max(offPlaneUnity, std::abs(sum - 1));
  }
  std::printf("in-plane reproduction error %g, off-plane partition-of-unity error %g\n", inPlaneError, offPlaneUnity);
  CHECK(finite);
  CHECK(inPlaneError <= 1e-10);
  CHECK(offPlaneUnity <= 1e-10);
}

TEST(OutsideEverySupportIsEmpty)
{
  const PointList centers = randomPoints(50, Vec3(0, 0, 0), Vec3(1, 1, 1), 8);
  const MLSBasis basis = randomBasis(centers, centers);
  ShapeFunctionValues phi;
  basis.evaluate(Vec3(10, 10, 10), phi, true);
  CHECK(phi.empty());
  CHECK(phi.gradient.empty());
}

TEST(InvalidRadiiAreRejected)
{
  const PointList centers = randomPoints(5, Vec3(0, 0, 0), Vec3(1, 1, 1), 9);
  CHECK_THROWS(MLSBasis(centers, std::vector<double>(5, 0.0)), InvalidInputException);
  CHECK_THROWS(MLSBasis(centers, std::vector<double>(4, 1.0)), InvalidInputException);
}

TEST_MAIN
