// Checks shared by the shape-function tests: values as dense vectors and analytic derivatives
// against central finite differences.
#pragma once

#include "Basis/ShapeFunctions.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>

namespace testgeometry
{
/// phi_j(x) for all j as a dense vector.
inline Eigen::VectorXd denseValues(const mlsdeform::ShapeFunctions& basis, const mlsdeform::Vec3& x)
{
  mlsdeform::ShapeFunctionValues phi;
  basis.evaluate(x, phi, false);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(basis.size());
  for (std::size_t a = 0; a < phi.index.size(); ++a)
    out[phi.index[a]] = phi.value[a];
  return out;
}

/// Largest differences between the analytic gradients/Laplacians and finite differences (steps
/// 1e-6 and 1e-4), with the largest analytic values as scales, over the points not skipped.
/// What the tests allow, and why: with values computed to delta (their round-off; <= 1e-12 for
/// the bases tested, see TestMLSBasis) and supports of radius sigma >= 0.16,
/// - central gradient, h1 = 1e-6: round-off delta / h1 <= 1e-6, truncation h1^2 / 6 |phi^(3)| ~
///   1e-12 x scale / sigma^2 ~ 1e-10 x scale: below 1e-6 x scale when the scale is >= 1;
/// - 3-point Laplacian, h2 = 1e-4: round-off 3 x 4 delta / h2^2 <= 1.2e-3, truncation
///   3 x h2^2 / 12 |phi^(4)| ~ 2.5e-9 x scale / sigma^2 ~ 1e-7 x scale: below 1e-3 x scale for
///   scales >= 10 (the Laplacian scales are >= 15 here; a wrong term is off by O(scale)).
struct DerivativeErrors
{
  double gradient = 0, laplacian = 0, gradientScale = 0, laplacianScale = 0;
  int compared = 0;
};
inline DerivativeErrors finiteDifferenceErrors(const mlsdeform::ShapeFunctions& basis, const mlsdeform::PointList& points,
  const std::function<bool(const mlsdeform::Vec3&)>& skip)
{
  const double h1 = 1e-6, h2 = 1e-4;
  DerivativeErrors e;
  mlsdeform::ShapeFunctionValues phi;
  for (const mlsdeform::Vec3& x : points)
  {
    if (skip(x))
      continue;
    ++e.compared;
    basis.evaluate(x, phi, true);
    const Eigen::VectorXd f0 = denseValues(basis, x);
    Eigen::VectorXd fdLaplacian = Eigen::VectorXd::Zero(basis.size());
    Eigen::MatrixXd fdGradient(basis.size(), 3);
    for (int d = 0; d < 3; ++d)
    {
      const mlsdeform::Vec3 u = mlsdeform::Vec3::Unit(d);
      fdGradient.col(d) = (denseValues(basis, x + h1 * u) - denseValues(basis, x - h1 * u)) / (2 * h1);
      fdLaplacian += (denseValues(basis, x + h2 * u) - 2 * f0 + denseValues(basis, x - h2 * u)) / (h2 * h2);
    }
    for (std::size_t a = 0; a < phi.index.size(); ++a)
    {
      const int j = phi.index[a];
      e.gradient = std::max(e.gradient, (fdGradient.row(j).transpose() - phi.gradient[a]).norm());
      e.laplacian = std::max(e.laplacian, std::abs(fdLaplacian[j] - phi.laplacian[a]));
      e.gradientScale = std::max(e.gradientScale, phi.gradient[a].norm());
      e.laplacianScale = std::max(e.laplacianScale, std::abs(phi.laplacian[a]));
    }
  }
  return e;
}
}
