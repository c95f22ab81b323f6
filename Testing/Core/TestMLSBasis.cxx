// Section 4: MLS shape functions reproduce linear fields, derivatives are analytic and right,
// coplanar samples are handled by the pseudo-inverse.
#include "MLSBasis.h"
#include "Sampling.h"
#include "TestGeometry.h"
#include "../TestHarness.h"

using namespace mlsdeform;
using testgeometry::randomPoints;

namespace
{
MLSBasis randomBasis(const PointList& centers, const PointList& covered, double cover = 5)
{
  return MLSBasis(centers, coverSupportRadii(centers, { &covered, &centers }, cover));
}

// phi_j(x) for all j as a dense vector, for finite differences.
Eigen::VectorXd dense(const MLSBasis& basis, const Vec3& x)
{
  ShapeFunctionValues phi;
  basis.evaluate(x, phi, false);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(basis.size());
  for (std::size_t a = 0; a < phi.index.size(); ++a)
    out[phi.index[a]] = phi.value[a];
  return out;
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
  ShapeFunctionValues phi;
  double gradientError = 0, laplacianError = 0, gradientScale = 0, laplacianScale = 0;
  const double h1 = 1e-6, h2 = 1e-4;
  int compared = 0;
  for (const Vec3& x : evaluation)
  {
    // w(r) = 1/2 cos(pi r/sigma) + 1/2 is C1 only at r = sigma: its second derivative jumps there,
    // so finite differences across a support boundary do not approximate the Laplacian.
    bool nearBoundary = false;
    for (std::size_t j = 0; j < centers.size(); ++j)
      nearBoundary = nearBoundary || std::abs((x - centers[j]).norm() - basis.supportRadii()[j]) < 10 * h2;
    if (nearBoundary)
      continue;
    ++compared;
    basis.evaluate(x, phi, true);
    const Eigen::VectorXd f0 = dense(basis, x);
    Eigen::VectorXd fdLaplacian = Eigen::VectorXd::Zero(basis.size());
    Eigen::MatrixXd fdGradient(basis.size(), 3);
    for (int d = 0; d < 3; ++d)
    {
      const Vec3 e = Vec3::Unit(d);
      fdGradient.col(d) = (dense(basis, x + h1 * e) - dense(basis, x - h1 * e)) / (2 * h1);
      fdLaplacian += (dense(basis, x + h2 * e) - 2 * f0 + dense(basis, x - h2 * e)) / (h2 * h2);
    }
    for (std::size_t a = 0; a < phi.index.size(); ++a)
    {
      const int j = phi.index[a];
      gradientError = std::max(gradientError, (fdGradient.row(j).transpose() - phi.gradient[a]).norm());
      laplacianError = std::max(laplacianError, std::abs(fdLaplacian[j] - phi.laplacian[a]));
      gradientScale = std::max(gradientScale, phi.gradient[a].norm());
      laplacianScale = std::max(laplacianScale, std::abs(phi.laplacian[a]));
    }
  }
  std::printf("%d points: gradient error %g (scale %g), Laplacian error %g (scale %g)\n", compared, gradientError, gradientScale, laplacianError, laplacianScale);
  CHECK(compared >= 25);
  CHECK(gradientError <= 1e-6 * gradientScale);
  CHECK(laplacianError <= 1e-3 * laplacianScale);
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
