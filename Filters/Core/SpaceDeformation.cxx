#include "SpaceDeformation.h"

#include "SubspaceOperators.h"

#include <cmath>

namespace mlsdeform
{
namespace
{
// Below this estimate of 1/cond the Cholesky factor is numerically singular in double precision.
constexpr double SingularReciprocalCondition = 1e-12;

// Below this, a tiny stretching term decides between equally bent results (see the header).
constexpr double MinimumStretchPerBend = 1e-6;

double largestSideOf(const PointList& a, const PointList& b)
{
  Vec3 lower = a.front(), upper = a.front();
  for (const PointList* list : { &a, &b })
  {
    for (const Vec3& p : *list)
    {
      lower = lower.cwiseMin(p);
      upper = upper.cwiseMax(p);
    }
  }
  return (upper - lower).maxCoeff();
}
}

SpaceDeformation::SpaceDeformation(const Samples& samples, const Progress& progress)
  : Basis(samples.centers, samples.supportRadius)
{
  if (samples.integrationPoints.empty() || samples.integrationPoints.size() != samples.volume.size())
  {
    throw InvalidInputException("no integration points with volumes");
  }
  requireFinite(samples.centers, "MLS samples");
  requireFinite(samples.integrationPoints, "integration points");
  double total = 0;
  for (double v : samples.volume)
  {
    if (!(v >= 0) || !std::isfinite(v))
    {
      throw InvalidInputException("integration point volumes must be finite and non-negative");
    }
    total += v;
  }
  if (!(total > 0))
  {
    throw InvalidInputException("the integration points have zero total volume");
  }
  const double l = largestSideOf(samples.centers, samples.integrationPoints);
  Energy = energyMatrix(Basis, samples.integrationPoints, samples.volume, 1 / std::sqrt(l), std::sqrt(l), progress);
}

void SpaceDeformation::setRegions(const std::vector<DirichletRegion>& regions)
{
  PointList positions;
  std::vector<double> scale;
  RegionSizes.clear();
  for (std::size_t r = 0; r < regions.size(); ++r)
  {
    const DirichletRegion& region = regions[r];
    if (region.positions.empty())
    {
      throw InvalidInputException("region " + std::to_string(r) + " selects no point");
    }
    requireFinite(region.positions, "region positions");
    positions.insert(positions.end(), region.positions.begin(), region.positions.end());
    scale.insert(scale.end(), region.positions.size(), std::sqrt(region.weight / region.positions.size()));
    RegionSizes.push_back(static_cast<int>(region.positions.size()));
  }
  std::vector<int> outside;
  RegionSubspace = subspaceMatrix(Basis, positions, &outside);
  if (!outside.empty())
  {
    throw InvalidInputException(std::to_string(outside.size()) + " region position(s) lie outside every MLS support, e.g. (" +
      std::to_string(positions[outside[0]].x()) + ", " + std::to_string(positions[outside[0]].y()) + ", " +
      std::to_string(positions[outside[0]].z()) + "); resample on a geometry that contains the regions");
  }
  RegionScale = Eigen::Map<Eigen::VectorXd>(scale.data(), static_cast<long>(scale.size()));
  Factor.reset();
}

void SpaceDeformation::factorize(const EnergyWeights& requested)
{
  EnergyWeights weights = requested;
  weights.stretch = std::max(weights.stretch, MinimumStretchPerBend * weights.bend);
  Weights = weights;
  Eigen::VectorXd energyWeight(Energy.rows());
  for (long i = 0; i < energyWeight.size(); ++i)
  {
    energyWeight[i] = i % 4 == 3 ? weights.bend : weights.stretch;
  }
  const SparseRowMatrix FPhi = RegionScale.asDiagonal() * RegionSubspace;
  RegionNormal = SparseMatrix(FPhi.transpose() * FPhi);
  System = SparseMatrix(Energy.transpose() * energyWeight.asDiagonal() * Energy) + weights.fix * RegionNormal;
  Factor = std::make_unique<SparseCholesky>();
  Factor->compute(System);
  ReciprocalCondition = Factor->reciprocalCondition();
  if (Factor->info() != Eigen::Success || !(ReciprocalCondition > SingularReciprocalCondition))
  {
    Factor.reset();
    throw SolverException("the deformation system (eq. 14) is singular (reciprocal condition " +
      std::to_string(ReciprocalCondition) +
      "): the handle and fixed regions and the energies do not determine every MLS coefficient; "
      "use a positive StretchWeight or BendWeight, or more integration points");
  }
}

Displacements SpaceDeformation::stackPrescribed(const std::vector<Displacements>& prescribed) const
{
  if (prescribed.size() != RegionSizes.size())
  {
    throw InvalidInputException("one prescribed displacement set per region is needed");
  }
  Displacements out(RegionScale.size(), 3);
  long offset = 0;
  for (std::size_t r = 0; r < prescribed.size(); ++r)
  {
    if (prescribed[r].rows() != RegionSizes[r] || !prescribed[r].allFinite())
    {
      throw InvalidInputException("region " + std::to_string(r) + ": prescribed displacements missing or not finite");
    }
    out.middleRows(offset, RegionSizes[r]) = prescribed[r];
    offset += RegionSizes[r];
  }
  return out;
}

Displacements SpaceDeformation::solve(const std::vector<Displacements>& prescribed, int corrections) const
{
  if (!Factor)
  {
    throw SolverException("solve() before a successful factorize()");
  }
  const Displacements dbar = stackPrescribed(prescribed);
  // b0 = gamma_f Phi^T F^T F dbar, the right-hand side of eq. 14: the only pass over the regions.
  const Displacements b0 = Weights.fix * multiplyTransposed(RegionSubspace, RegionScale.cwiseProduct(RegionScale).asDiagonal() * dbar);
  Displacements rhs = b0;
  Displacements w = Factor->solve(rhs);
  for (int i = 0; i < corrections; ++i)
  {
    // targets += dbar - Phi w, i.e. rhs += gamma_f Phi^T F^T F (dbar - Phi w) = b0 - gamma_f A w
    rhs += b0 - Weights.fix * (RegionNormal * w);
    w = Factor->solve(rhs);
  }
  if (!w.allFinite())
  {
    throw SolverException("the solution of eq. 14 is not finite");
  }
  return w;
}

std::vector<double> SpaceDeformation::regionResiduals(const Displacements& w, const std::vector<Displacements>& prescribed) const
{
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> d(RegionSubspace.rows(), 3);
  multiplyRows(RegionSubspace, w, 0, RegionSubspace.rows(), d.data());
  std::vector<double> out;
  long offset = 0;
  for (std::size_t r = 0; r < RegionSizes.size(); ++r)
  {
    out.push_back((d.middleRows(offset, RegionSizes[r]) - prescribed[r]).rowwise().norm().maxCoeff());
    offset += RegionSizes[r];
  }
  return out;
}
} // namespace mlsdeform
