// Section 4: MLS shape functions reproduce linear fields, derivatives are analytic and right,
// coplanar samples are handled by the pseudo-inverse.
#include "Basis/MLSBasis.h"
#include "Sampling/Sampling.h"
#include "ShapeFunctionChecks.h"
#include "TestGeometry.h"
#include "../TestHarness.h"

#include <Eigen/Dense>

#include <limits>

using namespace mlsdeform;
using namespace testgeometry;

namespace
{
MLSBasis randomBasis(const PointList& centers, const PointList& covered, double cover = 5)
{
  return MLSBasis(centers, coverSupportRadii(centers, { &covered, &centers }, cover));
}

// The condition number of the moment matrix at x in the shifted basis, S = sum_j w_j (c_j - cbar)
// (c_j - cbar)^T, over the eigenvalues the pseudo-inverse keeps (above 1e-8 of the largest, as in
// MLSBasis.cxx): the shape functions are computed to about eps x this per term.
double momentCondition(const MLSBasis& basis, const PointList& centers, const Vec3& x, const std::vector<int>& index)
{
  double W = 0;
  Vec3 centroid = Vec3::Zero();
  for (int j : index)
  {
    const double w = MLSBasis::weight((x - centers[j]).norm(), basis.supportRadii()[j]);
    W += w;
    centroid += w * centers[j];
  }
  centroid /= W;
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (int j : index)
    S += MLSBasis::weight((x - centers[j]).norm(), basis.supportRadii()[j]) * (centers[j] - centroid) * (centers[j] - centroid).transpose();
  const Eigen::Vector3d lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues();
  const double kept = lambda[0] > 1e-8 * lambda[2] ? lambda[0] : lambda[1];
  return lambda[2] / kept;
}

const double Epsilon = std::numeric_limits<double>::epsilon(); // 2.2e-16

}

TEST(WeightFunction)
{
  // cos^2(pi r / (2 sigma)): the cosine to a few ulps (HalfAngleIsLibmsCosineAndSine) and one
  // rounding of its square, values <= 1, so 1e-15 = 4.5 eps. Outside the support it is 0 by definition.
  CHECK_NEAR(MLSBasis::weight(0.0, 2.0), 1.0, 1e-15);
  CHECK_NEAR(MLSBasis::weight(1.0, 2.0), 0.5, 1e-15);
  CHECK_NEAR(MLSBasis::weight(2.0, 2.0), 0.0, 1e-15);
  CHECK_NEAR(MLSBasis::weight(3.0, 2.0), 0.0, 0.0);
}

TEST(HalfAngleIsLibmsCosineAndSine)
{
  // halfAngle against libm at x = pi/2 sqrt(u): libm's argument is x rounded (off by up to
  // ~4e-16 for x <= pi/2; cos and sin/x change by at most as much), both results round to within
  // an ulp or two of values <= 1, and the polynomials' terms (below 1.3) add a few roundings of
  // that size, so they agree to 1e-15 = 4.5 eps. The weight 1/2 cos(2x) + 1/2 likewise.
  double worst = 0, worstWeight = 0;
  for (int i = 1; i <= 100000; ++i)
  {
    for (double u : { i / 100000.0, std::nextafter(i / 100000.0, 0.0) })
    {
      const double x = M_PI / 2 * std::sqrt(u);
      const HalfAngle h = halfAngle(u);
      worst = std::max({ worst, std::abs(h.cosine - std::cos(x)), std::abs(h.sinc - std::sin(x) / x) });
      worstWeight = std::max(worstWeight, std::abs(MLSBasis::weight(std::sqrt(u), 1.0) - (0.5 * std::cos(M_PI * std::sqrt(u)) + 0.5)));
    }
  }
  std::printf("largest difference to libm over [0, 1]: %.3g, of the weight %.3g\n", worst, worstWeight);
  CHECK(worst <= 1e-15);
  CHECK(worstWeight <= 1e-15);
  const HalfAngle zero = halfAngle(0.0);
  CHECK(zero.cosine == 1 && zero.sinc == 1); // exact at the centre: the weight is 1 there
  CHECK_NEAR(halfAngle(1.0).cosine, 0.0, 1e-16); // cos(pi/2): the weight meets 0 at the support's edge
}

TEST(PartitionOfUnityAndLinearReproduction)
{
  const PointList centers = randomPoints(400, Vec3(0, 0, 0), Vec3(1, 2, 1), 1);
  const PointList evaluation = randomPoints(1000, Vec3(0, 0, 0), Vec3(1, 2, 1), 2);
  const MLSBasis basis = randomBasis(centers, evaluation);
  ShapeFunctionValues phi;
  double unity = 0, linear = 0, gradient = 0, laplacian = 0;
  double condition = 0, gradientScale = 0, laplacianScale = 0, extent = 0;
  std::size_t terms = 0;
  for (const Vec3& x : evaluation)
  {
    basis.evaluate(x, phi, true);
    CHECK(phi.index.size() >= 5); // the cover of 5
    condition = std::max(condition, momentCondition(basis, centers, x, phi.index));
    terms = std::max(terms, phi.index.size());
    extent = std::max(extent, x.norm());
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
      gradientScale = std::max(gradientScale, phi.gradient[a].norm());
      laplacianScale = std::max(laplacianScale, std::abs(phi.laplacian[a]));
    }
    unity = std::max(unity, std::abs(sum - 1));
    linear = std::max(linear, (reproduced - x).norm());
    gradient = std::max({ gradient, sumGradient.norm(), (jacobian - Eigen::Matrix3d::Identity()).norm() });
    laplacian = std::max({ laplacian, std::abs(sumLaplacian), laplacianOfLinear.norm() });
  }
  std::printf("max errors: unity %g, linear %g, gradient %g, laplacian %g\n", unity, linear, gradient, laplacian);
  // Exact in exact arithmetic (MLS reproduces its linear basis), so only round-off: each term is
  // computed to eps x the moment matrix's condition, and sums of n terms of size v round to
  // n eps cond v, with v = 1 (values), |x| (linear field), the largest gradient or Laplacian
  // entry (derivatives); a factor 2 for the two parts of each function (1/W and the linear one).
  const double roundOff = 2 * static_cast<double>(terms) * Epsilon * condition;
  std::printf("round-off n eps cond = %g (n = %zu, cond %g), |x| <= %g, scales: gradient %g, Laplacian %g\n", roundOff,
    terms, condition, extent, gradientScale, laplacianScale);
  CHECK(unity <= roundOff);
  CHECK(linear <= roundOff * extent);
  CHECK(gradient <= roundOff * gradientScale * std::max(1.0, extent));   // derivatives of 1 and x: 0 and I
  CHECK(laplacian <= roundOff * laplacianScale * std::max(1.0, extent)); // Laplacians of 1 and x: 0
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
  // Enough points compared: each lies in ~0.6 skipped shells (300 supports of radius ~0.3, shells
  // 2e-3 wide), so ~e^-0.6 x 50 = 27 are expected (standard deviation 3.5); 10 is 5 below.
  CHECK(e.compared >= 10);
  // the finite-difference error bounds of ShapeFunctionChecks.h, with value round-off <= 1e-12
  // (n eps cond above) and scales >= 1
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
  double inPlaneError = 0, offPlaneUnity = 0, condition = 0;
  std::size_t terms = 0;
  bool finite = true;
  for (const Vec3& x : inPlane)
  {
    basis.evaluate(x, phi, true);
    condition = std::max(condition, momentCondition(basis, centers, x, phi.index));
    terms = std::max(terms, phi.index.size());
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
    condition = std::max(condition, momentCondition(basis, centers, x, phi.index));
    terms = std::max(terms, phi.index.size());
    double sum = 0;
    for (std::size_t a = 0; a < phi.index.size(); ++a)
    {
      sum += phi.value[a];
      finite = finite && std::isfinite(phi.value[a]) && phi.gradient[a].allFinite() && std::isfinite(phi.laplacian[a]);
    }
    offPlaneUnity = std::max(offPlaneUnity, std::abs(sum - 1));
  }
  std::printf("in-plane reproduction error %g, off-plane partition-of-unity error %g\n", inPlaneError, offPlaneUnity);
  // round-off as in PartitionOfUnityAndLinearReproduction, with the condition over the two kept
  // eigenvalues (the pseudo-inverse drops the zero one); |x| <= 1.8 for the linear field
  const double roundOff = 2 * static_cast<double>(terms) * Epsilon * condition;
  std::printf("round-off n eps cond = %g (n = %zu, cond %g)\n", roundOff, terms, condition);
  CHECK(finite);
  CHECK(inPlaneError <= 1.8 * roundOff);
  CHECK(offPlaneUnity <= roundOff);
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
