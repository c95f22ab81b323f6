#include "SpaceDeformation.h"

#include "MLSBasis.h"
#include "RadialBasis.h"

#include <algorithm>
#include <cmath>

namespace mlsdeform
{
namespace
{
// Below this estimate of 1/cond the Cholesky factor is numerically singular in double precision.
constexpr double SingularReciprocalCondition = 1e-12;
// DeformationEnergy::ridge of the global RBF bases with volumetric energies.
constexpr double GlobalBasisRidge = 1e-9;

// Below this, a tiny stretching term decides between equally bent results (see the header).
constexpr double MinimumStretchPerBend = 1e-6;

// An accelerated step is rejected when the fixed-point residual exceeds this multiple of the
// smallest residual since the last restart: Anderson iterates are not monotone, and a strict
// decrease rejected good steps (rigid scene: 3.9x instead of 10x fewer iterations), while the
// bound keeps the residual from creeping upward.
constexpr double SafeguardGrowth = 3.0;
}

SpaceDeformation::SpaceDeformation(std::shared_ptr<const ShapeFunctions> basis, DeformationEnergy energy, double length)
  : Basis(std::move(basis))
  , Length(length)
{
  if (!Basis || Basis->size() == 0 || energy.stretch.cols() != static_cast<long>(Basis->size()) ||
    energy.bend.cols() != static_cast<long>(Basis->size()) || !(length > 0))
  {
    throw InvalidInputException("a subspace needs shape functions, energies on them and a positive length");
  }
  Energy = normalMatrices(energy);
}

std::shared_ptr<const ShapeFunctions> makeBasis(BasisKind kind, const Samples& samples)
{
  switch (kind)
  {
    case BasisKind::Wendland:
      return std::make_shared<RadialBasis>(RadialKernel::Wendland, samples.centers, samples.supportRadius);
    case BasisKind::Gaussian:
      return std::make_shared<RadialBasis>(RadialKernel::Gaussian, samples.centers, samples.supportRadius);
    case BasisKind::Biharmonic:
      return std::make_shared<RadialBasis>(RadialKernel::Biharmonic, samples.centers, samples.supportRadius);
    case BasisKind::Triharmonic:
      return std::make_shared<RadialBasis>(RadialKernel::Triharmonic, samples.centers, samples.supportRadius);
    case BasisKind::MLS:
      break;
  }
  return std::make_shared<MLSBasis>(samples.centers, samples.supportRadius);
}

SpaceDeformation::SpaceDeformation(const Samples& samples, BasisKind kind, const Progress& progress)
  : Basis(makeBasis(kind, samples))
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
  PointList sampled = samples.centers;
  sampled.insert(sampled.end(), samples.integrationPoints.begin(), samples.integrationPoints.end());
  const double l = largestSide(sampled);
  Length = l;
  const double N = static_cast<double>(samples.integrationPoints.size());
  Energy = volumetricEnergyNormals(*Basis, samples.integrationPoints, samples.volume, 1 / std::sqrt(l * N), std::sqrt(l / N), progress);
  if (kind == BasisKind::Biharmonic || kind == BasisKind::Triharmonic)
  {
    // dense kernel systems are badly conditioned (nearly dependent columns, r^3 growing with
    // distance); a tiny ridge keeps the Cholesky factorization stable
    Energy.ridge = GlobalBasisRidge;
  }
}

void SpaceDeformation::setRegions(const std::vector<DirichletRegion>& regions)
{
  PointList positions;
  RegionScale.clear();
  RegionBegin.assign(1, 0);
  for (std::size_t r = 0; r < regions.size(); ++r)
  {
    const DirichletRegion& region = regions[r];
    if (region.positions.empty())
    {
      throw InvalidInputException("region " + std::to_string(r) + " selects no point");
    }
    requireFinite(region.positions, "region positions");
    positions.insert(positions.end(), region.positions.begin(), region.positions.end());
    RegionScale.push_back(region.weight / region.positions.size());
    RegionBegin.push_back(static_cast<long>(positions.size()));
  }
  std::vector<int> outside;
  RegionSubspace = subspaceMatrix(*Basis, positions, &outside);
  if (!outside.empty())
  {
    throw InvalidInputException(std::to_string(outside.size()) + " region position(s) lie outside every MLS support, e.g. (" +
      std::to_string(positions[outside[0]].x()) + ", " + std::to_string(positions[outside[0]].y()) + ", " +
      std::to_string(positions[outside[0]].z()) + "); resample on a geometry that contains the regions");
  }
  RegionNormals.clear();
  for (std::size_t r = 0; r < RegionScale.size(); ++r)
  {
    const long n = RegionBegin[r + 1] - RegionBegin[r];
    RegionNormals.push_back(weightedGram(RegionSubspace, RegionBegin[r], RegionBegin[r + 1], Eigen::VectorXd::Constant(n, RegionScale[r])));
  }
  Factor.reset();
}

void SpaceDeformation::setConstraints(const std::vector<ShapeConstraint>& constraints, ConstraintFormulation formulation)
{
  Constraints = constraints.empty() ? nullptr : std::make_unique<ShapeConstraints>(*Basis, constraints, formulation);
  Factor.reset();
}

void SpaceDeformation::factorize(const EnergyWeights& requested)
{
  EnergyWeights weights = requested;
  weights.stretch = std::max(weights.stretch, MinimumStretchPerBend * weights.bend);
  Weights = weights;
  System = weights.stretch * Energy.stretch + weights.bend * Energy.bend;
  for (const SparseMatrix& A : RegionNormals)
  {
    System += weights.fix * A;
  }
  if (Constraints)
  {
    System += weights.constraint * Constraints->normalMatrix();
  }
  if (Energy.ridge > 0)
  {
    const Eigen::VectorXd ridge = Eigen::VectorXd::Constant(System.rows(), Energy.ridge * System.diagonal().maxCoeff());
    System += SparseMatrix(ridge.asDiagonal());
  }
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

void SpaceDeformation::checkPrescribed(const std::vector<Displacements>& prescribed) const
{
  if (prescribed.size() != RegionScale.size())
  {
    throw InvalidInputException("one prescribed displacement set per region is needed");
  }
  for (std::size_t r = 0; r < prescribed.size(); ++r)
  {
    if (prescribed[r].rows() != RegionBegin[r + 1] - RegionBegin[r] || !prescribed[r].allFinite())
    {
      throw InvalidInputException("region " + std::to_string(r) + ": prescribed displacements missing or not finite");
    }
  }
}

SpaceDeformation::Solution SpaceDeformation::solve(const std::vector<Displacements>& prescribed, const IterationSettings& settings) const
{
  if (!Factor)
  {
    throw SolverException("solve() before a successful factorize()");
  }
  checkPrescribed(prescribed);
  // b_r = Phi_r^T F_r^2 dbar_r; the right-hand side of eq. 14 is gamma_f sum_r b_r.
  std::vector<Displacements> b;
  Displacements b0 = Displacements::Zero(Basis->size(), 3);
  for (std::size_t r = 0; r < prescribed.size(); ++r)
  {
    b.push_back(RegionScale[r] * multiplyTransposed(RegionSubspace, RegionBegin[r], RegionBegin[r + 1], prescribed[r]));
    b0 += Weights.fix * b.back();
  }
  Solution solution;
  Displacements& w = solution.w;
  if (!Constraints)
  {
    w = Factor->solve(b0);
  }
  else
  {
    // Section 6: local step (projections of the current positions; the rest shape first), then
    // the global step (eq. 17) with them: w -> G(w), optionally Anderson-accelerated.
    using Vector = Eigen::VectorXd;
    const long size = 3 * static_cast<long>(Basis->size());
    auto flat = [size](Displacements& m) { return Eigen::Map<Vector>(m.data(), size); };
    w = Displacements::Zero(Basis->size(), 3);
    std::vector<PointList> positions = Constraints->positions(w);
    std::vector<PointList> projections = Constraints->project(positions);
    std::vector<Vector> previousG, previousF; // the last G(w) and G(w) - w
    Displacements fallback;                   // G of the iterate before an accelerated step
    double bestResidual = std::numeric_limits<double>::infinity(); // since the last restart
    bool accelerated = false;
    solution.converged = false;
    for (int i = 0; i < settings.maxIterations && !solution.converged; ++i)
    {
      Displacements g = Factor->solve(b0 + Weights.constraint * Constraints->rightHandSide(positions, projections));
      const Vector f = flat(g) - flat(w);
      solution.iterations = i + 1;
      if (accelerated && f.norm() > SafeguardGrowth * bestResidual)
      {
        // Safeguard: the accelerated step let the fixed-point residual grow; take the plain step
        // from the previous iterate instead and restart the history.
        w = fallback;
        positions = Constraints->positions(w);
        projections = Constraints->project(positions);
        previousF.clear();
        previousG.clear();
        accelerated = false;
        bestResidual = std::numeric_limits<double>::infinity();
        continue;
      }
      Displacements next = g;
      if (settings.andersonDepth > 0 && !previousF.empty())
      {
        // min |f - dF gamma| over the differences of the last residuals, next = g - dG gamma
        const long m = static_cast<long>(previousF.size());
        Eigen::MatrixXd dF(size, m), dG(size, m);
        for (long j = 0; j < m; ++j)
        {
          dF.col(j) = f - previousF[j];
          dG.col(j) = flat(g) - previousG[j];
        }
        flat(next) = flat(g) - dG * dF.colPivHouseholderQr().solve(f);
      }
      if (settings.andersonDepth > 0)
      {
        previousF.push_back(f);
        previousG.push_back(flat(g));
        if (static_cast<int>(previousF.size()) > settings.andersonDepth)
        {
          previousF.erase(previousF.begin());
          previousG.erase(previousG.begin());
        }
      }
      accelerated = settings.andersonDepth > 0 && previousF.size() > 1;
      fallback = g;
      bestResidual = std::min(bestResidual, f.norm());
      std::vector<PointList> nextPositions = Constraints->positions(next);
      const std::vector<double> moved = ShapeConstraints::largestDistances(nextPositions, positions);
      w = next;
      positions = std::move(nextPositions);
      projections = Constraints->project(positions);
      solution.converged = *std::max_element(moved.begin(), moved.end()) <= settings.tolerance * Length;
    }
    solution.constraintResidual = ShapeConstraints::largestDistances(positions, projections);
  }
  if (!w.allFinite())
  {
    throw SolverException("the solution of eq. 14 is not finite");
  }
  for (std::size_t r = 0; r < prescribed.size(); ++r)
  {
    const double squared = (w.transpose() * (RegionNormals[r] * w)).trace() - 2 * (w.transpose() * b[r]).trace() +
      RegionScale[r] * prescribed[r].squaredNorm();
    const double weight = RegionScale[r] * (RegionBegin[r + 1] - RegionBegin[r]);
    solution.rmsResidual.push_back(weight > 0 ? std::sqrt(std::max(0.0, squared) / weight) : 0.0);
  }
  return solution;
}

} // namespace mlsdeform
