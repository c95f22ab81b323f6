// Moving-least-squares shape functions (paper section 4):
//   phi_j(x) = p(x)^T M^+(x) p(c_j) w_j(x),   M(x) = sum_j w_j(x) p(c_j) p(c_j)^T,
// linear basis p = (1, x, y, z), compactly supported weight w(r) = 1/2 cos(pi r / sigma_j) + 1/2,
// M^+ the SVD pseudo-inverse, with analytic gradients and Laplacians (Fries & Matthies [5]).
#pragma once

#include "Common/KdTree.h"
#include "Basis/ShapeFunctions.h"

namespace mlsdeform
{
/// The weight's half angle t/2 = pi/2 sqrt(u) for u = (r / sigma)^2 in [0, 1]: cos(t/2) and
/// sin(t/2) / (t/2), Taylor polynomials in u to degree 10 (truncation below 2e-17, terms below
/// 1.3 in size). Pure arithmetic: the same bits on any x86-64 CPU (libm's cos and sin have
/// CPU-specific variants, with FMA or without, that need not round alike), no square root and no
/// argument reduction in the weight loops.
struct HalfAngle
{
  double cosine;
  double sinc;
};
HalfAngle halfAngle(double u);

class MLSBasis : public ShapeFunctions
{
public:
  /// Samples c_j with support radii sigma_j > 0.
  MLSBasis(const PointList& centers, const std::vector<double>& supportRadii);

  /// Evaluates at x; the result is empty when x lies outside every support.
  void evaluate(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const override;
  bool candidatesInBox(const Vec3& lower, const Vec3& upper, std::vector<int>& candidates) const override;
  void narrowCandidates(const Vec3& lower, const Vec3& upper, const std::vector<int>& candidates, std::vector<int>& narrowed) const override;
  void evaluateAmong(const Vec3& x, const std::vector<int>& candidates, ShapeFunctionValues& out, bool withDerivatives) const override;

  /// w(r) = 1/2 cos(pi r / sigma) + 1/2 = cos^2(pi r / (2 sigma)) for r < sigma, else 0.
  static double weight(double r, double sigma);

  std::size_t size() const override { return Centers.size(); }
  const PointList& centers() const { return Centers; }
  const std::vector<double>& supportRadii() const { return Radii; }

private:
  /// Evaluates the shape functions out.index, those whose support contains x, given their squared
  /// distances |x - c_j|^2 in out.value.
  void evaluateSupports(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const;

  PointList Centers;
  std::vector<double> Radii;
  KdTree Supports;
};
} // namespace mlsdeform
