// The derivative of the fixed point of section 6's local/global iteration, w = G(w): implicit
// differentiation gives (I - M) dw = r with M = dG/dw, a linear system known by its products
// M v only. GMRES (Saad & Schultz 1986) solves it; the iteration's contraction (|M| < 1 where it
// converges) keeps I - M well conditioned.
#pragma once

#include <Eigen/Core>

#include <functional>

namespace mlsdeform
{
/// The step of the central difference (F(w + h v) - F(w - h v)) / 2h that differentiates the
/// projections along v: h |v|_max = 1e-4 of the model's length. Truncation error is
/// O((h |v| / R)^2) for a projection whose shape has radius R (1e-8 for R = the model's length,
/// 1e-4 for a cylinder of 1% of it); noise is the projections' own accuracy over the step: the
/// cylinder fit's axis search stops at 1e-10 rad (1e-6 relative), round-off 1e-12; 0 for v = 0.
/// (Measured on the suite's scenes: 1e-5 traded a planar patch's 3e-8 for a cylinder's 5e-5.)
double centralDifferenceStep(double length, double largestComponent);

/// GMRES on (I - M) x = r from x = 0, without restart, until |r - (I - M) x| <= 1e-10 |r| (the
/// central differences' noise floor is about 1e-11). Throws SolverException when 300 products
/// did not reach it (the fixed point is not a contraction there).
Eigen::VectorXd solveIdentityMinus(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& M, const Eigen::VectorXd& r);
} // namespace mlsdeform
