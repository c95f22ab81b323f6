// Section 4: the radial basis functions compared with MLS (Wendland, Gaussian, biharmonic,
// triharmonic): kernel values, analytic derivatives, and the linear polynomials of the global ones.
#include "../TestHarness.h"
#include "RadialBasis.h"
#include "Sampling.h"
#include "ShapeFunctionChecks.h"
#include "TestGeometry.h"

#include <Eigen/Dense>

#include <cmath>

using namespace mlsdeform;
using namespace testgeometry;

namespace
{
const RadialKernel Kernels[4] = { RadialKernel::Wendland, RadialKernel::Gaussian, RadialKernel::Biharmonic, RadialKernel::Triharmonic };
const char* KernelNames[4] = { "Wendland", "Gaussian", "Biharmonic", "Triharmonic" };

double valueAt(const RadialBasis& basis, const Vec3& x, int j)
{
  return denseValues(basis, x)[j];
}
}

TEST(CompactKernelsAreOneAtTheCenterAndVanishAtTheSupport)
{
  const PointList center = { Vec3(0, 0, 0) };
  const RadialBasis wendland(RadialKernel::Wendland, center, { 2.0 }), gaussian(RadialKernel::Gaussian, center, { 2.0 });
  CHECK_NEAR(valueAt(wendland, Vec3(0, 0, 0), 0), 1.0, 1e-15);
  CHECK_NEAR(valueAt(gaussian, Vec3(0, 0, 0), 0), 1.0, 1e-15);
  // (1 - t)^4 (4t + 1) at t = 1/2: 3/16
  CHECK_NEAR(valueAt(wendland, Vec3(1, 0, 0), 0), 3.0 / 16, 1e-15);
  // (exp(-9 t^2) - exp(-9)) / (1 - exp(-9)) at t = 1/2
  CHECK_NEAR(valueAt(gaussian, Vec3(0, 1, 0), 0), (std::exp(-2.25) - std::exp(-9.0)) / (1 - std::exp(-9.0)), 1e-15);
  // continuous at the support radius, nothing outside it
  CHECK(std::abs(valueAt(wendland, Vec3(0, 0, 1.9999999), 0)) < 1e-20);
  CHECK(std::abs(valueAt(gaussian, Vec3(0, 0, 1.9999999), 0)) < 1e-9);
  ShapeFunctionValues outside;
  wendland.evaluate(Vec3(2.5, 0, 0), outside, true);
  CHECK(outside.empty());
  CHECK(wendland.size() == 1);
  CHECK_THROWS(RadialBasis(RadialKernel::Gaussian, center, { 0.0 }), InvalidInputException);
  CHECK_THROWS(RadialBasis(RadialKernel::Wendland, { Vec3(std::nan(""), 0, 0) }, { 1.0 }), InvalidInputException);
}

TEST(DerivativesMatchFiniteDifferences)
{
  const PointList centers = randomPoints(60, Vec3(0, 0, 0), Vec3(1, 1, 1), 11);
  const PointList evaluation = randomPoints(30, Vec3(0.1, 0.1, 0.1), Vec3(0.9, 0.9, 0.9), 12);
  const std::vector<double> radii(centers.size(), 0.45);
  for (int kind = 0; kind < 4; ++kind)
  {
    const RadialBasis basis(Kernels[kind], centers, radii);
    // The truncated Gaussian's derivative jumps at the support radius and the biharmonic kernel
    // r is not differentiable at its center: finite differences there are no reference.
    const DerivativeErrors e = finiteDifferenceErrors(basis, evaluation, [&](const Vec3& x) {
      for (const Vec3& c : centers)
        if (std::abs((x - c).norm() - 0.45) < 1e-3 || (x - c).norm() < 1e-3)
          return true;
      return false;
    });
    std::printf("%s, %d points: gradient error %g (scale %g), Laplacian error %g (scale %g)\n", KernelNames[kind], e.compared,
      e.gradient, e.gradientScale, e.laplacian, e.laplacianScale);
    CHECK(e.compared >= 20);
    CHECK(e.gradient <= 1e-6 * e.gradientScale);
    CHECK(e.laplacian <= 1e-3 * e.laplacianScale);
  }
}

TEST(GlobalBasesContainLinearMaps)
{
  // Least-squares fits of a linear map f(x) = A x + b at 400 points with 80 centers: exact for the
  // global kernels (their linear polynomials), not for a compact kernel, which does not even
  // reproduce constants.
  const PointList centers = randomPoints(80, Vec3(0, 0, 0), Vec3(2, 1, 1), 21);
  const PointList points = randomPoints(400, Vec3(0, 0, 0), Vec3(2, 1, 1), 22);
  const std::vector<double> radii = coverSupportRadii(centers, { &points, &centers }, 5);
  for (int kind = 0; kind < 4; ++kind)
  {
    const RadialBasis basis(Kernels[kind], centers, radii);
    Eigen::MatrixXd Phi(points.size(), basis.size());
    Eigen::VectorXd f(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      Phi.row(i) = denseValues(basis, points[i]).transpose();
      f[i] = 0.3 + 2 * points[i].x() - points[i].y() + 0.5 * points[i].z();
    }
    const Eigen::VectorXd w = Phi.colPivHouseholderQr().solve(f);
    const double residual = (Phi * w - f).cwiseAbs().maxCoeff();
    std::printf("%s: size %zu, largest residual of a linear map %g\n", KernelNames[kind], basis.size(), residual);
    if (kind >= 2)
    {
      CHECK(basis.size() == centers.size() + 4);
      CHECK(residual < 1e-8);
    }
    else
    {
      CHECK(basis.size() == centers.size());
      CHECK(residual > 1e-4);
    }
  }
}

TEST_MAIN
