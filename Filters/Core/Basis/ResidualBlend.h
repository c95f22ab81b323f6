// The blend functions of exact targets: the subspace solution d = Phi w of eq. 14 meets the
// prescribed displacements dbar only in the least-squares sense (the penalty gamma_f leaves 1-3%
// of a handle's motion on a CFD case), and no choice of w makes it exact at thousands of region
// points. The correction field
//   c(x) = sum_j psi_j(x) r_j,   r_j = dbar_j - Phi(x_j) w      (the residuals at the sites x_j)
//   psi_j(x) = beta(|x - x_j| / R) omega_j(x) / sum_i omega_i(x)
//   omega_j(x) = (1 - |x - x_j| / d_{K+1})^2 / |x - x_j|^2      (j among the K sites nearest x)
//   beta(t) = (1 - t)^4 (4 t + 1) for t < 1, else 0            (Wendland's C2 profile)
// added to d makes the output exact at every site: omega_j grows without bound at x_j, so
// psi_j(x_j) = 1 and psi_i(x_j) = 0. It is a Shepard interpolation of the residuals (a convex
// combination: |c| <= max |r_j|), continuous where the K nearest change (the weight of the K-th
// vanishes at the (K+1)-th's distance, Franke and Nielson's localized form), with zero gradient
// at the sites, faded out over R by beta (beta'(0) = 0, |beta'| <= 2.1, so |grad c| stays within
// 2.1 max|r| / R of the interpolation's own). c is linear in r, so derivatives of the output
// carry it exactly. As shape functions over the sites, the operators of SubspaceOperators.h
// evaluate it at the points and transpose it for the reverse mode.
#pragma once

#include "Common/KdTree.h"
#include "Common/PositionIndex.h"
#include "Basis/ShapeFunctions.h"

namespace mlsdeform
{
class ResidualBlend : public ShapeFunctions
{
public:
  /// The sites x_j (distinct positions: uniqueSites; throws InvalidInputException otherwise) and
  /// the fade radius R > 0.
  ResidualBlend(const PointList& sites, double radius);

  /// psi_j(x) (no derivatives): empty beyond R of every site, one entry at a site.
  void evaluate(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const override;

  std::size_t size() const override { return Sites.distinct().size(); }

private:
  double Radius;
  PositionIndex Sites; // x_j, found by position
  KdTree Tree;
};

/// The distinct positions among positions, in order of first appearance; siteOf[i] is the index
/// of positions[i]'s site (equal positions bit for bit, +0 = -0).
PointList uniqueSites(const PointList& positions, std::vector<long>& siteOf);
} // namespace mlsdeform
