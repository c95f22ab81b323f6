// A subspace deformation d(x) = sum_j w_j phi_j(x) (paper sections 3-5): minimizes
//   gamma_s |G w|^2 + gamma_b |L w|^2 + gamma_f |F (Phi w - dbar)|^2
// over the k x 3 coefficients w by the normal equations (eq. 10, 11, 14)
//   (gamma_s G^T G + gamma_b L^T L + gamma_f Phi^T F^T F Phi) w = gamma_f Phi^T F^T F dbar,
// factorized once (CHOLMOD) and solved again for every new dbar (a design variation). The shape
// functions and the energies G, L are given: the MLS subspace with volumetric integration points
// (section 5, built from Samples), or a mesh's own piecewise linear functions with its shell
// operators (section 3), or any basis with those operators applied to Phi (eq. 11).
// Every term is normalized by its number of rows, as section 7 prescribes for the weights
// ("normalized by the number of constraints prescribed for a given type and region"): each region
// r contributes weight_r / n_r sum_{i in r} |d(x_i) - dbar_i|^2, and the N integration points
// E_stretch = 1/N sum_i V_i / l |grad d(q_i)|^2 and E_bend = 1/N sum_i V_i l |Lap d(q_i)|^2, where
// the model's length l (the largest side of the sampled box) makes them scale like a squared
// displacement, independent of the model's units. With this the paper's weights keep its order
// of priority: targets (gamma_f ~ 1000) before constraints (gamma_c ~ 10) before smoothness (~ 1).
#pragma once

#include "Sampling/Sampling.h"
#include "Solver/ShapeConstraints.h"
#include "Solver/SparseCholesky.h"
#include "Basis/SubspaceOperators.h"

#include <memory>

namespace mlsdeform
{
/// The shape functions of section 4 a subspace is built from on the samples (MLSBasis.h,
/// RadialBasis.h).
enum class BasisKind
{
  MLS,
  Wendland,
  Gaussian,
  Biharmonic,
  Triharmonic
};

/// The basis of that kind on the samples' centers (compact ones with their support radii).
std::shared_ptr<const ShapeFunctions> makeBasis(BasisKind kind, const Samples& samples);

struct EnergyWeights
{
  double stretch = 0.0;     // gamma_s
  double bend = 1.0;        // gamma_b
  double fix = 1000.0;      // gamma_f
  double constraint = 10.0; // gamma_c (eq. 17)
  bool operator==(const EnergyWeights& o) const
  {
    return stretch == o.stretch && bend == o.bend && fix == o.fix && constraint == o.constraint;
  }
};

/// The alternating (local/global) optimization of section 6.
struct IterationSettings
{
  int maxIterations = 5000;
  /// Stop when the constrained points are estimated to lie within tolerance x the length scale
  /// of the iteration's fixed point: a map contracting at rate rho leaves its plain step G(w)
  /// within rho / (1 - rho) times the step's length of the fixed point, with rho estimated as
  /// the largest |G(w) - G(w_j)| / |w - w_j| over the last iterates w_j (exact for the linearized
  /// map in the directions the iteration explores).
  double tolerance = 1e-7;
  /// Anderson acceleration of the fixed point w -> G(w) over the last andersonDepth steps
  /// (Walker & Ni 2011), safeguarded: an accelerated step after which the fixed-point residual
  /// |G(w) - w| exceeds 3x its smallest value since the last restart is replaced by the plain
  /// step and the history restarts (in the spirit of Peng et al. 2018, with the residual
  /// instead of the energy, which the local step of the sparse formulation does not decrease).
  /// 0 = the plain iteration of the paper.
  int andersonDepth = 5;
};

/// Positions whose displacement is prescribed (a handle or a fixed region).
struct DirichletRegion
{
  PointList positions;
  double weight = 1.0; // relative weight of this region within gamma_f
};

class SpaceDeformation
{
public:
  /// Builds the basis on the samples (MLS by default) and G, L at the integration points (eq. 12, 13).
  explicit SpaceDeformation(const Samples& samples, BasisKind kind = BasisKind::MLS, const Progress& progress = {});

  /// A subspace with its energies (rows normalized as above) and the model's length l, the
  /// scale of the iteration tolerance.
  SpaceDeformation(std::shared_ptr<const ShapeFunctions> basis, DeformationEnergy energy, double length);

  /// Phi at the region positions and F. Throws InvalidInputException for an empty region or a
  /// position outside every support. Rows of Phi known at region positions (numbered over all
  /// regions' positions in order) are viewed in `reuse` rather than evaluated again: its rows must
  /// live unchanged until the next setRegions.
  void setRegions(const std::vector<DirichletRegion>& regions, const KnownRows& reuse = {});

  /// Geometric constraints (section 6); none by default. Throws InvalidInputException for a set
  /// with too few points or outside every support.
  void setConstraints(const std::vector<ShapeConstraint>& constraints, ConstraintFormulation formulation);

  /// Factorizes the matrix of eq. 14 (eq. 17 with constraints); throws SolverException when it
  /// is singular. A stretching
  /// weight of at least 1e-6 * bend is always used: pure bending does not determine motions
  /// that bend nothing, such as a shear normal to a flat configuration, and the tiny stretching
  /// term picks the least stretched of the equally bent results. The bending energy (eq. 13)
  /// measures the Laplacian only, at the integration points: many samples over few of them (a
  /// fine surface sampling: the sphereChannel case with k = 10,000) leave harmonic combinations
  /// that bend nothing there and that the tiny term barely determines. Such a singular system
  /// is factorized again with a stretch weight of 1e-4 and then 1e-2 times the bend weight
  /// (regularizingStretch() says which): the deformation is then that much more membrane-like
  /// (its first derivatives penalized too), which changes the displacements by about that
  /// share. Still singular, it throws.
  void factorize(const EnergyWeights& weights);

  /// The stretch weight that a singular system was factorized with instead of the requested
  /// one; 0 when the requested weights (with the least share above) determined it.
  double regularizingStretch() const { return RegularizingStretch; }

  /// Whether the system is factorized for these weights (as given to factorize) with the current
  /// regions and constraints: setRegions and setConstraints discard the factor.
  bool isFactorizedFor(const EnergyWeights& weights) const { return !Factors.empty() && FactorizedFor == weights; }

  struct Solution
  {
    Displacements w;                        // the MLS coefficients, k x 3
    std::vector<double> rmsResidual;        // per region: sqrt(mean_i |d(x_i) - dbar_i|^2)
    std::vector<double> constraintResidual; // per constraint: max distance to its projection
    int iterations = 0;                     // local/global iterations (0 without constraints)
    bool converged = true;
    double estimatedError = 0;              // estimated distance of the constrained points from the fixed point
    std::vector<Vec3> axes;                 // the cylinder fits' axes at the last iterate (the tangent's projections start there)
  };

  /// Solves eq. 14 for the prescribed displacements of each region (one row per region
  /// position, in the order given to setRegions; viewed, not copied). The only passes over the
  /// region points are the right-hand sides b_r = Phi_r^T F_r^2 dbar_r (Phi_r^T formed by
  /// setRegions); residuals come from |F_r(Phi_r w - dbar_r)|^2 = w^T A_r w - 2 w^T b_r + |F_r dbar_r|^2.
  /// With constraints, the local/global iteration of section 6 follows: projections of the
  /// current constrained positions, then eq. 17 with them, until the estimated distance from its
  /// fixed point is below tolerance * lengthScale() or maxIterations. The answer depends on the
  /// arguments and the set-up only (not on earlier solves), so solves may run concurrently.
  Solution solve(const std::vector<PointDisplacementsView>& prescribed, const IterationSettings& settings = {}) const;
  Solution solve(const std::vector<PointDisplacements>& prescribed, const IterationSettings& settings = {}) const;

  /// Whether the solution is linear in the prescribed displacements: no constraint, or slip
  /// planes normal to an axis only (no local/global iteration).
  bool isLinear() const { return !Constraints || !Constraints->iterative(); }

  /// The derivative dw of solve()'s coefficients along the prescribed displacements' derivative
  /// dPrescribed (one set per region, as for solve), at the solution `at` of solve(). Linear: the
  /// system's solution for dPrescribed's right-hand side, exact. With the iteration of section 6:
  /// implicit differentiation of its fixed point w = G(w) = A^-1 (b0 + gamma_c F(w)),
  ///   (I - gamma_c A^-1 dF/dw) dw = A^-1 db0,
  /// solved by GMRES on the same factorization, with dF/dw v, the projections' derivative along
  /// v, by central differences (LinearizedFixedPoint.h). Throws SolverException when GMRES does
  /// not reach its tolerance.
  Displacements tangent(const std::vector<PointDisplacementsView>& dPrescribed, const Solution& at) const;

  /// Reverse mode of a linear solution: for H = dJ/dw (k x 3, the objective's gradient with
  /// respect to the coefficients), dJ/d(dbar) at every region position (stacked in the order of
  /// setRegions): gamma_f F_r^2 Phi_r A^-1 H (eq. 14 is symmetric). Throws SolverException when
  /// the solution is not linear (isLinear()).
  PointDisplacements prescribedGradient(const Displacements& H) const;

  /// Every constraint set's positions x_t + Phi_t w (sets in the order given to setConstraints).
  std::vector<PointList> constraintPositions(const Displacements& w) const;
  /// Every set's projection of positions (the local step; the cylinder fits start from axes).
  std::vector<PointList> projectConstraints(const std::vector<PointList>& positions, std::vector<Vec3> axes) const;

  /// Per constraint set: the largest distance of its points, moved by Phi w plus added (one row
  /// per point of every set, the sets in the order given to setConstraints), from their
  /// projection (the cylinder fits starting from axes; empty: from the rest fits). The residual
  /// of a displacement that is more than Phi w (the exact targets' correction).
  std::vector<double> constraintResiduals(const Displacements& w, const PointDisplacements& added, std::vector<Vec3> axes) const;

  /// Phi w at every region position (stacked in the order of setRegions): where the solution
  /// puts the targets (their residuals are dbar - Phi w); the positions in `known` (Phi w at the
  /// rows given to setRegions) copied from it.
  PointDisplacements regionDisplacements(const Displacements& w, const KnownProduct& known = {}) const;
  /// Phi_T^T e for one row of e per region position (the transpose of regionDisplacements).
  Displacements regionTransposed(const PointDisplacements& e) const;

  /// The model's length l (for MLS samples, the largest side of the sampled box).
  double lengthScale() const { return Length; }

  const ShapeFunctions& basis() const { return *Basis; }
  /// N, the points at which the bending energy is integrated.
  std::size_t numberOfIntegrationPoints() const { return Energy.points; }
  double reciprocalCondition() const { return ReciprocalCondition; }

private:
  void checkPrescribed(const std::vector<PointDisplacementsView>& prescribed) const;
  /// The right-hand side of eq. 14, gamma_f sum_r b_r, and each region's b_r = Phi_r^T F_r^2 dbar_r.
  Displacements targetRightHandSide(const std::vector<PointDisplacementsView>& prescribed, std::vector<Displacements>* perRegion) const;
  /// F(w): the constraints' right-hand side for the projections of the positions of w (the
  /// projections start from the cylinder axes given).
  Displacements constraintRightHandSide(const Displacements& w, std::vector<Vec3> axes) const;
  /// The system's solution for the right-hand sides b (one column per coordinate).
  Displacements solveSystem(const Displacements& b) const;
  /// Section 6's local/global iteration from w = 0 for the right-hand side b0 of eq. 14.
  void iterateConstraints(const Displacements& b0, const IterationSettings& settings, Solution& solution) const;

  std::shared_ptr<const ShapeFunctions> Basis;
  EnergyNormals Energy;
  GatheredRows RegionSubspace;     // Phi at the stacked region positions (views of the known rows given to setRegions)
  std::vector<double> RegionScale; // F_r^2 = weight_r / n_r
  std::vector<long> RegionBegin;   // first row of each region in RegionSubspace, and the end
  EnergyWeights Weights;       // as used (stretch at least 1e-6 bend)
  EnergyWeights FactorizedFor; // as requested
  std::vector<SparseMatrix> RegionNormals; // A_r = Phi_r^T F_r^2 Phi_r (k x k) per region
  std::unique_ptr<ShapeConstraints> Constraints;
  double Length = 1;
  SparseMatrix System;             // the matrix of eq. 14 (17)
  /// The factor of eq. 14 (17): one for all three coordinates, or one per coordinate when slip
  /// planes normal to an axis add to that coordinate's system only.
  std::vector<std::unique_ptr<SparseCholesky>> Factors;
  double ReciprocalCondition = 0;
  double RegularizingStretch = 0;
};
} // namespace mlsdeform
