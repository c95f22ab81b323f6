// Section 4: the radial basis functions compared with MLS (Wendland, Gaussian, biharmonic,
// triharmonic): kernel values, analytic derivatives, and the linear polynomials of the global ones.
#include "../TestHarness.h"
#include "Basis/RadialBasis.h"
#include "Sampling/Sampling.h"
#include "ShapeFunctionChecks.h"
#include "TestGeometry.h"

#include <Eigen/Dense>

#include <cmath>
#include <limits>

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
  // closed forms evaluated with a few roundings (and one exp) on values <= 1: a few ulps, 1e-15 = 4.5 eps
  CHECK_NEAR(valueAt(wendland, Vec3(0, 0, 0), 0), 1.0, 1e-15);
  CHECK_NEAR(valueAt(gaussian, Vec3(0, 0, 0), 0), 1.0, 1e-15);
  // (1 - t)^4 (4t + 1) at t = 1/2: 3/16
  CHECK_NEAR(valueAt(wendland, Vec3(1, 0, 0), 0), 3.0 / 16, 1e-15);
  // (exp(-9 t^2) - exp(-9)) / (1 - exp(-9)) at t = 1/2
  CHECK_NEAR(valueAt(gaussian, Vec3(0, 1, 0), 0), (std::exp(-2.25) - std::exp(-9.0)) / (1 - std::exp(-9.0)), 1e-15);
  // continuous at the support radius, nothing outside it: 1e-7 inside it (1 - t = 5e-8), the
  // Wendland kernel is (1 - t)^4 (4t + 1) = 3e-29, and the truncated Gaussian its slope at sigma,
  // 18 e^-9 / sigma = 1.1e-3, times 1e-7: 1.1e-10 (an untruncated one would still be e^-9 = 1.2e-4)
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
    // enough points compared: each lies in ~0.3 skipped shells (60 supports of radius 0.45, shells
    // 2e-3 wide, partly outside the box), so ~e^-0.3 x 30 = 22 are expected (standard deviation
    // 2.4); 10 is 5 below
    CHECK(e.compared >= 10);
    // the finite-difference error bounds of ShapeFunctionChecks.h: the kernels are closed forms,
    // computed to a few eps (values <= 1), and the scales are >= 1 and >= 15
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
    // Householder QR is backward stable: for a consistent system the computed residual is the
    // round-off of k reflections, k eps (|Phi| |w| + |f|) (Frobenius and 2-norms), whatever the
    // condition of Phi.
    const double roundOff = static_cast<double>(basis.size()) * std::numeric_limits<double>::epsilon() * (Phi.norm() * w.norm() + f.norm());
    std::printf("%s: size %zu, largest residual of a linear map %g (round-off bound %g)\n", KernelNames[kind], basis.size(),
      residual, roundOff);
    if (kind >= 2)
    {
      CHECK(basis.size() == centers.size() + 4);
      CHECK(residual < roundOff);
    }
    else
    {
      // not in the span: the residual is 1e-4 of the map's values (up to 4.3), orders of
      // magnitude above any round-off (the bound printed)
      CHECK(basis.size() == centers.size());
      CHECK(residual > 1e-4 && residual > 1e3 * roundOff);
    }
  }
}

TEST_MAIN
