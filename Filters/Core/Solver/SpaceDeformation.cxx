#include "Solver/SpaceDeformation.h"

#include "Common/BoundingBox.h"
#include "Solver/LinearizedFixedPoint.h"

#include "Basis/MLSBasis.h"
#include "Basis/RadialBasis.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <iomanip>
#include <limits>
#include <sstream>

namespace mlsdeform
{
namespace
{
// Below this estimate of 1/cond the Cholesky factor is numerically singular in double precision.
constexpr double SingularReciprocalCondition = 1e-12;
// DeformationEnergy::ridge of the global RBF bases with volumetric energies.
constexpr double GlobalBasisRidge = 1e-9;

// The stretch weights per bend weight tried in turn while the system is singular (see the
// header): first the least, a tiny stretching term that decides between equally bent results,
// then the regularizing ones.
constexpr std::array<double, 3> StretchPerBendShares{ 1e-6, 1e-4, 1e-2 };

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

void SpaceDeformation::setRegions(const std::vector<DirichletRegion>& regions, const KnownRows& reuse)
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
  RegionSubspace = gatherRows(*Basis, positions, reuse, &outside, RegionBegin); // each region read as stored
  if (!outside.empty())
  {
    throw InvalidInputException(std::to_string(outside.size()) + " region position(s) lie outside every MLS support, e.g. (" +
      std::to_string(positions[outside[0]].x()) + ", " + std::to_string(positions[outside[0]].y()) + ", " +
      std::to_string(positions[outside[0]].z()) + "); resample on a geometry that contains the regions");
  }
  RegionNormals.clear();
  RegionNormals.reserve(RegionScale.size()); // Eigen's sparse matrices are copied, not moved, when a vector grows
  for (std::size_t r = 0; r < RegionScale.size(); ++r)
  {
    const long n = RegionBegin[r + 1] - RegionBegin[r];
    RegionNormals.push_back(weightedGram(RegionSubspace, RegionBegin[r], RegionBegin[r + 1], Eigen::VectorXd::Constant(n, RegionScale[r])));
  }
  Factors.clear();
}

void SpaceDeformation::setConstraints(const std::vector<ShapeConstraint>& constraints, ConstraintFormulation formulation)
{
  Constraints = constraints.empty() ? nullptr : std::make_unique<ShapeConstraints>(*Basis, constraints, formulation);
  Factors.clear();
}

void SpaceDeformation::factorize(const EnergyWeights& requested)
{
  const int systems = Constraints && Constraints->hasAxisSlips() ? 3 : 1; // slip planes normal to an axis: that coordinate's own system
  bool positiveDefinite = false;
  EnergyWeights weights = requested;
  for (std::size_t attempt = 0; attempt < StretchPerBendShares.size(); ++attempt)
  {
    const double share = StretchPerBendShares[attempt];
    if (attempt > 0 && (requested.bend <= 0 || requested.stretch >= share * requested.bend))
    {
      continue; // a share the requested stretch already holds: the same system
    }
    weights.stretch = std::max(requested.stretch, share * requested.bend);
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
    Factors.clear();
    ReciprocalCondition = std::numeric_limits<double>::infinity();
    positiveDefinite = true;
    for (int a = 0; a < systems && positiveDefinite && ReciprocalCondition > SingularReciprocalCondition; ++a)
    {
      auto factor = std::make_unique<SparseCholesky>();
      positiveDefinite =
        systems == 1 ? factor->factorize(System) : factor->factorize(System + weights.constraint * Constraints->axisNormal(a));
      ReciprocalCondition = std::min(ReciprocalCondition, positiveDefinite ? factor->reciprocalCondition() : 0.0);
      Factors.push_back(std::move(factor));
    }
    if (positiveDefinite && ReciprocalCondition > SingularReciprocalCondition)
    {
      Weights = weights;
      RegularizingStretch = attempt > 0 ? weights.stretch : 0;
      FactorizedFor = requested;
      return;
    }
  }
  Factors.clear();
  std::ostringstream reason;
  reason << "the deformation system (eq. 14) is singular: ";
  if (!positiveDefinite)
  {
    reason << "its Cholesky factorization met a pivot that is not positive";
  }
  else
  {
    reason << "its reciprocal condition " << std::setprecision(3) << ReciprocalCondition << " is below " << SingularReciprocalCondition;
  }
  reason << ". With " << System.rows() << " MLS samples, " << Energy.points << " integration points and bend weight "
         << requested.bend << ", even a stretch weight of " << weights.stretch
         << " leaves some sample's coefficient undetermined: a sample whose support holds few integration points is seen "
            "by little but round-off, and the regions must fix the deformation's translation. Use a larger StretchWeight, "
            "Cover or IntegrationPointRatio, or fewer samples (NumberOfSamples)";
  throw SolverException(reason.str());
}

Displacements SpaceDeformation::solveSystem(const Displacements& b) const
{
  if (Factors.size() == 1)
  {
    return Factors[0]->solve(b);
  }
  Displacements x(b.rows(), 3);
  for (int a = 0; a < 3; ++a)
  {
    x.col(a) = Factors[a]->solveColumn(b.col(a));
  }
  return x;
}

void SpaceDeformation::checkPrescribed(const std::vector<PointDisplacementsView>& prescribed) const
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

SpaceDeformation::Solution SpaceDeformation::solve(const std::vector<PointDisplacements>& prescribed, const IterationSettings& settings) const
{
  std::vector<PointDisplacementsView> views;
  for (const PointDisplacements& d : prescribed)
  {
    views.emplace_back(d.data(), d.rows(), 3);
  }
  return solve(views, settings);
}

Displacements SpaceDeformation::targetRightHandSide(const std::vector<PointDisplacementsView>& prescribed, std::vector<Displacements>* perRegion) const
{
  // b_r = Phi_r^T F_r^2 dbar_r; the right-hand side of eq. 14 is gamma_f sum_r b_r.
  const long k = static_cast<long>(Basis->size());
  if (perRegion)
  {
    perRegion->assign(prescribed.size(), Displacements::Zero(k, 3));
  }
  Displacements b0 = Displacements::Zero(k, 3);
  for (std::size_t r = 0; r < prescribed.size(); ++r)
  {
    if (!prescribed[r].any())
    {
      continue; // a fixed region: the product would be zeros, at the cost of a pass over Phi_r
    }
    const Displacements br = RegionScale[r] * multiplyTransposed(RegionSubspace, RegionBegin[r], RegionBegin[r + 1], prescribed[r]);
    b0 += Weights.fix * br;
    if (perRegion)
    {
      (*perRegion)[r] = br;
    }
  }
  return b0;
}

SpaceDeformation::Solution SpaceDeformation::solve(const std::vector<PointDisplacementsView>& prescribed, const IterationSettings& settings) const
{
  if (Factors.empty())
  {
    throw SolverException("solve() before a successful factorize()");
  }
  checkPrescribed(prescribed);
  std::vector<Displacements> b;
  const Displacements b0 = targetRightHandSide(prescribed, &b);
  Solution solution;
  if (Constraints && Constraints->iterative())
  {
    iterateConstraints(b0, settings, solution);
  }
  else
  {
    solution.w = solveSystem(b0);
    if (Constraints) // axis-normal slip planes only: exact, their residuals for the record
    {
      std::vector<Vec3> axes = Constraints->restAxes();
      const std::vector<PointList> positions = Constraints->positions(solution.w);
      solution.constraintResidual = ShapeConstraints::largestDistances(positions, Constraints->project(positions, axes));
    }
  }
  const Displacements& w = solution.w;
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

void SpaceDeformation::iterateConstraints(const Displacements& b0, const IterationSettings& settings, Solution& solution) const
{
  // Section 6: local step (projections of the current positions; the rest shape first), then
  // the global step (eq. 17) with them: w -> G(w), optionally Anderson-accelerated. Everything
  // the iteration carries (iterates, history, the cylinder fits' axes) lives here.
  using Vector = Eigen::VectorXd;
  const long size = 3 * static_cast<long>(Basis->size());
  auto flat = [size](const Displacements& m) { return Eigen::Map<const Vector>(m.data(), size); };
  const int depth = std::max(0, settings.andersonDepth);
  Displacements& w = solution.w;
  w = Displacements::Zero(Basis->size(), 3);
  std::vector<Vec3> axes = Constraints->restAxes();
  std::vector<PointList> positions = Constraints->positions(w);
  std::vector<PointList> projections = Constraints->project(positions, axes);
  std::deque<Vector> previousW, previousG; // the last iterates w_j and their plain steps G(w_j)
  Displacements fallback;                  // G of the iterate before an accelerated step
  double bestResidual = std::numeric_limits<double>::infinity(); // since the last restart
  bool accelerated = false;
  bool historyHasStart = false; // previousW.front() is w = 0
  solution.converged = false;
  solution.estimatedError = std::numeric_limits<double>::infinity();
  for (int i = 0; i < settings.maxIterations; ++i)
  {
    Displacements g = solveSystem(b0 + Weights.constraint * Constraints->rightHandSide(positions, projections));
    const Vector f = flat(g) - flat(w);
    solution.iterations = i + 1;
    if (accelerated && f.norm() > SafeguardGrowth * bestResidual)
    {
      // Safeguard: the accelerated step let the fixed-point residual grow; take the plain step
      // from the previous iterate instead and restart the history.
      w = fallback;
      positions = Constraints->positions(w);
      projections = Constraints->project(positions, axes);
      previousW.clear();
      previousG.clear();
      historyHasStart = false;
      accelerated = false;
      bestResidual = std::numeric_limits<double>::infinity();
      continue;
    }
    // Convergence: the plain step's move of the constrained points and the contraction rate rho
    // seen between this iterate and the last ones; G(w) lies within rho / (1 - rho) x move of
    // the fixed point (see IterationSettings::tolerance).
    std::vector<PointList> stepped = Constraints->positions(g);
    const double move = ShapeConstraints::largestDistance(stepped, positions);
    double contraction = -1; // unknown
    // (not from the start w = 0: its step carries the whole deformation to the targets and
    // says nothing about the contraction near the fixed point)
    for (std::size_t j = historyHasStart ? 1 : 0; j < previousW.size(); ++j)
    {
      const double apart = (flat(w) - previousW[j]).norm();
      if (apart > 0)
      {
        contraction = std::max(contraction, (flat(g) - previousG[j]).norm() / apart);
      }
    }
    const double error = move == 0 ? 0.0
      : contraction >= 0 && contraction < 1 ? move * contraction / (1 - contraction)
                                            : std::numeric_limits<double>::infinity();
    if (error <= settings.tolerance * Length)
    {
      w = g;
      positions = std::move(stepped);
      projections = Constraints->project(positions, axes);
      solution.converged = true;
      solution.estimatedError = error;
      break;
    }
    Displacements next = g;
    const bool extrapolated = depth > 0 && !previousW.empty();
    if (extrapolated)
    {
      // min |f - dF gamma| over the differences of the last residuals f_j = G(w_j) - w_j,
      // next = g - dG gamma
      const long m = static_cast<long>(previousW.size());
      Eigen::MatrixXd dF(size, m), dG(size, m);
      for (long j = 0; j < m; ++j)
      {
        dF.col(j) = f - (previousG[j] - previousW[j]);
        dG.col(j) = flat(g) - previousG[j];
      }
      Eigen::Map<Vector>(next.data(), size) = flat(g) - dG * dF.colPivHouseholderQr().solve(f);
    }
    historyHasStart = historyHasStart || i == 0;
    previousW.push_back(flat(w));
    previousG.push_back(flat(g));
    if (static_cast<int>(previousW.size()) > std::max(1, depth))
    {
      previousW.pop_front();
      previousG.pop_front();
      historyHasStart = false;
    }
    accelerated = extrapolated;
    fallback = g;
    bestResidual = std::min(bestResidual, f.norm());
    positions = extrapolated ? Constraints->positions(next) : std::move(stepped);
    w = std::move(next);
    projections = Constraints->project(positions, axes);
  }
  solution.constraintResidual = ShapeConstraints::largestDistances(positions, projections);
  solution.axes = std::move(axes);
}

Displacements SpaceDeformation::constraintRightHandSide(const Displacements& w, std::vector<Vec3> axes) const
{
  const std::vector<PointList> positions = Constraints->positions(w);
  return Constraints->rightHandSide(positions, Constraints->project(positions, axes));
}

Displacements SpaceDeformation::tangent(const std::vector<PointDisplacementsView>& dPrescribed, const Solution& at) const
{
  if (Factors.empty())
  {
    throw SolverException("tangent() before a successful factorize()");
  }
  checkPrescribed(dPrescribed);
  const Displacements direct = solveSystem(targetRightHandSide(dPrescribed, nullptr)); // A^-1 db0
  if (isLinear())
  {
    return direct;
  }
  if (at.w.rows() != static_cast<long>(Basis->size()) || at.axes.size() != Constraints->restAxes().size())
  {
    throw SolverException("tangent() needs the solution of solve() it differentiates");
  }
  // M v = gamma_c A^-1 dF/dw v, dF/dw v by central differences of F at the fixed point
  const long k = static_cast<long>(Basis->size());
  const auto M = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const Eigen::Map<const Displacements> direction(v.data(), k, 3);
    const double step = centralDifferenceStep(Length, direction.cwiseAbs().maxCoeff());
    if (!(step > 0))
    {
      return Eigen::VectorXd::Zero(v.size());
    }
    const Displacements dF =
      (constraintRightHandSide(at.w + step * direction, at.axes) - constraintRightHandSide(at.w - step * direction, at.axes)) / (2 * step);
    const Displacements Mv = solveSystem(Weights.constraint * dF);
    return Eigen::Map<const Eigen::VectorXd>(Mv.data(), Mv.size());
  };
  const Eigen::VectorXd r = Eigen::Map<const Eigen::VectorXd>(direct.data(), direct.size());
  const Eigen::VectorXd dw = solveIdentityMinus(M, r);
  return Eigen::Map<const Displacements>(dw.data(), k, 3);
}

PointDisplacements SpaceDeformation::prescribedGradient(const Displacements& H) const
{
  if (Factors.empty())
  {
    throw SolverException("prescribedGradient() before a successful factorize()");
  }
  if (!isLinear())
  {
    throw SolverException("the reverse mode through the constraint iteration is not available: use tangent() per design variable");
  }
  // dJ/d(dbar_r) = (d w / d dbar_r)^T H = gamma_f F_r^2 Phi_r A^-T H, A symmetric
  const Displacements lambda = solveSystem(H);
  PointDisplacements gradient(RegionSubspace.rows(), 3);
  multiplyRows(RegionSubspace, lambda, 0, RegionSubspace.rows(), gradient.data());
  for (std::size_t r = 0; r < RegionScale.size(); ++r)
  {
    gradient.middleRows(RegionBegin[r], RegionBegin[r + 1] - RegionBegin[r]) *= Weights.fix * RegionScale[r];
  }
  return gradient;
}

std::vector<PointList> SpaceDeformation::constraintPositions(const Displacements& w) const
{
  return Constraints ? Constraints->positions(w) : std::vector<PointList>();
}

std::vector<PointList> SpaceDeformation::projectConstraints(const std::vector<PointList>& positions, std::vector<Vec3> axes) const
{
  if (!Constraints)
  {
    return {};
  }
  if (axes.empty())
  {
    axes = Constraints->restAxes();
  }
  return Constraints->project(positions, axes);
}

std::vector<double> SpaceDeformation::constraintResiduals(const Displacements& w, const PointDisplacements& added, std::vector<Vec3> axes) const
{
  if (!Constraints)
  {
    return {};
  }
  std::vector<PointList> positions = Constraints->positions(w);
  long row = 0;
  for (PointList& set : positions)
  {
    for (Vec3& y : set)
    {
      y += added.row(row++).transpose();
    }
  }
  if (axes.empty())
  {
    axes = Constraints->restAxes();
  }
  return ShapeConstraints::largestDistances(positions, Constraints->project(positions, axes));
}

PointDisplacements SpaceDeformation::regionDisplacements(const Displacements& w, const KnownProduct& known) const
{
  PointDisplacements d(RegionSubspace.rows(), 3);
  multiplyRows(RegionSubspace, w, 0, RegionSubspace.rows(), d.data(), Into::Write, known);
  return d;
}

Displacements SpaceDeformation::regionTransposed(const PointDisplacements& e) const
{
  return multiplyTransposed(RegionSubspace, 0, RegionSubspace.rows(), e);
}

} // namespace mlsdeform
