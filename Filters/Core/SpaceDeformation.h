// The MLS space deformation of paper section 5: minimizes
//   gamma_s |G w|^2 + gamma_b |L w|^2 + gamma_f |F (Phi w - dbar)|^2
// over the k x 3 coefficients w by the normal equations (eq. 14)
//   (gamma_s G^T G + gamma_b L^T L + gamma_f Phi^T F^T F Phi) w = gamma_f Phi^T F^T F dbar,
// factorized once (CHOLMOD) and solved again for every new dbar (a design variation).
// The energies are the paper's integrals made independent of the model's units with its length
// l (the largest side of the sampled box): E_stretch = sum_i V_i / l |grad d(q_i)|^2 and
// E_bend = sum_i V_i l |Lap d(q_i)|^2 both scale like a squared displacement, as does the fix
// term, where each region r contributes weight_r / n_r sum_{i in r} |d(x_i) - dbar_i|^2
// (weights normalized by the number of points, section 7). For a model of unit size these are
// exactly the paper's energies.
#pragma once

#include "MLSBasis.h"
#include "Sampling.h"
#include "SparseCholesky.h"

#include <memory>

namespace mlsdeform
{
struct EnergyWeights
{
  double stretch = 0.0; // gamma_s
  double bend = 1.0;    // gamma_b
  double fix = 1000.0;  // gamma_f
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
  /// Builds the MLS basis on the samples and G, L at the integration points (eq. 12, 13).
  explicit SpaceDeformation(const Samples& samples, const Progress& progress = {});

  /// Phi at the region positions and F. Throws InvalidInputException for an empty region or a
  /// position outside every support.
  void setRegions(const std::vector<DirichletRegion>& regions);

  /// Factorizes the matrix of eq. 14; throws SolverException when it is singular. A stretching
  /// weight of at least 1e-6 * bend is always used: pure bending does not determine motions
  /// that bend nothing, such as a shear normal to a flat configuration, and the tiny stretching
  /// term picks the least stretched of the equally bent results.
  void factorize(const EnergyWeights& weights);

  struct Solution
  {
    Displacements w;                 // the MLS coefficients, k x 3
    std::vector<double> rmsResidual; // per region: sqrt(mean_i |d(x_i) - dbar_i|^2)
  };

  /// Solves eq. 14 for the prescribed displacements of each region (one row per region
  /// position, in the order given to setRegions). With corrections > 0, the targets are then
  /// shifted by the remaining residual and eq. 14 solved again (a Bregman / augmented Lagrangian
  /// iteration): each correction costs one back-substitution and k-sized products, and brings
  /// the result closer to min E subject to d(x_i) = dbar_i than the penalty gamma_f alone.
  /// The only passes over the region points are the right-hand sides b_r = Phi_r^T F_r^2 dbar_r;
  /// residuals come from |F_r(Phi_r w - dbar_r)|^2 = w^T A_r w - 2 w^T b_r + |F_r dbar_r|^2.
  Solution solve(const std::vector<Displacements>& prescribed, int corrections = 0) const;

  const MLSBasis& basis() const { return Basis; }
  std::size_t numberOfIntegrationPoints() const { return Energy.rows() / 4; }
  double reciprocalCondition() const { return ReciprocalCondition; }

private:
  void checkPrescribed(const std::vector<Displacements>& prescribed) const;

  MLSBasis Basis;
  SparseRowMatrix Energy;          // D = [G; L] interleaved, see SubspaceOperators.h
  SparseRowMatrix RegionSubspace;  // Phi at the stacked region positions
  std::vector<double> RegionScale; // F_r^2 = weight_r / n_r
  std::vector<long> RegionBegin;   // first row of each region in RegionSubspace, and the end
  EnergyWeights Weights;
  std::vector<SparseMatrix> RegionNormals; // A_r = Phi_r^T F_r^2 Phi_r (k x k) per region
  SparseMatrix RegionNormal;       // A = sum_r A_r
  SparseMatrix System;             // the matrix of eq. 14
  std::unique_ptr<SparseCholesky> Factor;
  double ReciprocalCondition = 0;
};
} // namespace mlsdeform
