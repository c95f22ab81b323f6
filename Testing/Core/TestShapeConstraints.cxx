// Section 6: the local/global iteration keeps geometric constraints during the deformation.
#include "../TestHarness.h"
#include "Solver/ConstraintProjections.h"
#include "Basis/MLSBasis.h"
#include "Solver/SpaceDeformation.h"
#include "Basis/SubspaceOperators.h"
#include "TestGeometry.h"

#include <chrono>
#include <cstring>

#include <omp.h>

using namespace mlsdeform;
using testgeometry::maxDistance;

namespace
{
// The bar [0,3] x [0,1] x [0,1], clamped: fixed for x <= 0.5, handle x >= 2.5 lifted by 0.5, so
// that the middle bends (S-shaped).
struct BentBar
{
  SamplingDomain box = testgeometry::tetrahedralBox(12, Vec3(3, 1, 1));
  Samples samples;
  std::vector<DirichletRegion> regions;
  std::vector<PointDisplacements> prescribed;
  Vec3 motion;
  explicit BentBar(const Vec3& handleMotion = Vec3(0, 0, 0.5), int surfaceSamples = 300, int volumeSamples = 100)
    : motion(handleMotion)
  {
    SamplingParameters p;
    p.numberOfSurfaceSamples = surfaceSamples;
    p.numberOfVolumeSamples = volumeSamples;
    // the paper's uniform sampling, on which the penalty balances below were stated (this box's
    // end faces have 3 times smaller triangles: following them would move samples to the ends)
    p.followMeshGrading = false;
    p.randomSeed = getenv("SEED") ? atoi(getenv("SEED")) : 0; samples = sampleDomain(box, p);
    regions.resize(2);
    for (const Vec3& x : box.points)
    {
      if (x.x() > 2.5 - 1e-9)
        regions[0].positions.push_back(x);
      if (x.x() < 0.5 + 1e-9)
        regions[1].positions.push_back(x);
    }
    prescribed = { motion.transpose().replicate(regions[0].positions.size(), 1),
      Displacements::Zero(regions[1].positions.size(), 3) };
  }
  PointList select(bool (*inside)(const Vec3&)) const
  {
    PointList out;
    for (const Vec3& x : box.points)
      if (inside(x))
        out.push_back(x);
    return out;
  }
};

struct Result
{
  PointList constrained; // deformed positions of the constrained set
  double handleError = 0, fixedError = 0;
  SpaceDeformation::Solution solution;
};

// Two iterations that share a fixed point agree within this fraction of the diagonal: each stops
// at an estimated distance of tolerance x length from it (IterationSettings::tolerance; the bar's
// length is 3), 2 x 1e-7 x 3 / sqrt(11) = 1.8e-7 of the diagonal for the two. The estimate,
// move x rho / (1 - rho), is exact for the linearized iteration only, and with rho near 1 (1e3
// plain iterations) an error in 1 - rho scales it: 100 x the tolerance allows 1 - rho to be
// overestimated 50-fold in each run. That is still far below the gap to a different fixed point,
// of the size of the constraint's effect (the formulations differed by 1.8e-3 of the diagonal
// before the deferred correction; the unconstrained violation is 1e-2).
double sameFixedPoint()
{
  return 100 * IterationSettings().tolerance * 3 / std::sqrt(11.0);
}

// A kept constraint (Fig. 6 a, b), by the penalty balances of the paper's weights (section 7).
// Every term is a mean square of a length (SpaceDeformation.h), so a violation v of a mode whose
// energy stiffness is a settles where a (v0 - v) = gamma_c v: v = v0 a / (a + gamma_c). The
// stiffness is not a constant of the model: it grows as the constrained set flattens (in the
// pipeline's planarity test the residual falls as gamma_c^-0.45 from gamma_c = 10 to 80, not as
// 1 / gamma_c), and with the sampling (the ratio v / v0 here ranged 0.07 to 0.13 over random
// seeds 0 to 5, the former bound gamma_b / gamma_c = 0.1 held for some seeds only). What the
// weights promise is that the constraint dominates its mode, a <= gamma_c: v <= v0 / 2. The
// targets balance the same way: what pulls them off is at most gamma_b + gamma_c, against
// gamma_f, so their misfit is below (gamma_b + gamma_c) / gamma_f = 1.1% of the motion (was 2%).
// That balance is one of mean squares; the strips move rigidly, which the subspace reproduces,
// so their misfit is about uniform and the largest one checked here is the RMS to first order.
void checkKept(double residual, double unconstrained, double handleError, double fixedError, double motion)
{
  const EnergyWeights w; // the weights deform() uses
  CHECK(residual <= unconstrained / 2);
  const double targets = (w.bend + w.constraint) / w.fix * motion;
  CHECK(handleError <= targets && fixedError <= targets);
}

Result deform(const BentBar& bar, const std::vector<ShapeConstraint>& constraints, ConstraintFormulation formulation,
  int andersonDepth = 5, double constraintWeight = 10)
{
  SpaceDeformation model(bar.samples);
  model.setRegions(bar.regions);
  model.setConstraints(constraints, formulation);
  model.factorize(EnergyWeights{ 0, 1, 1000, constraintWeight }); // the paper's weights by default
  Result result;
  IterationSettings settings;
  settings.andersonDepth = andersonDepth;
  result.solution = model.solve(bar.prescribed, settings);
  const PointList& set = constraints.empty() ? PointList() : constraints[0].positions;
  auto moved = [&](const PointList& x) {
    const Displacements d = subspaceMatrix(model.basis(), x) * result.solution.w;
    PointList y = x;
    for (std::size_t i = 0; i < x.size(); ++i)
      y[i] += d.row(i).transpose();
    return y;
  };
  result.constrained = moved(set);
  const PointList handle = moved(bar.regions[0].positions), fixed = moved(bar.regions[1].positions);
  for (std::size_t i = 0; i < handle.size(); ++i)
    result.handleError = std::max(result.handleError, (handle[i] - bar.regions[0].positions[i] - bar.motion).norm());
  for (std::size_t i = 0; i < fixed.size(); ++i)
    result.fixedError = std::max(result.fixedError, (fixed[i] - bar.regions[1].positions[i]).norm());
  return result;
}

}

TEST(PlanarityIsKept)
{
  BentBar bar;
  const double diagonal = std::sqrt(11.0);
  const PointList top = bar.select([](const Vec3& x) { return x.z() > 1 - 1e-9 && x.x() > 0.5 - 1e-9 && x.x() < 1.25 + 1e-9; });
  const std::vector<ShapeConstraint> planarity = { { ConstraintType::Planarity, top, 1.0 } };
  // unconstrained: the same set, deformed, is far from planar
  SpaceDeformation free(bar.samples);
  free.setRegions(bar.regions);
  free.factorize(EnergyWeights{});
  const Displacements d = subspaceMatrix(free.basis(), top) * free.solve(bar.prescribed).w;
  PointList bent = top;
  for (std::size_t i = 0; i < top.size(); ++i)
    bent[i] += d.row(i).transpose();
  const double unconstrained = maxDistance(bent, projectToPlane(bent));

  std::vector<Result> results; // plain sparse, plain mean-centered, accelerated sparse, accelerated mean-centered
  for (int depth : { 0, 5 })
    for (ConstraintFormulation formulation : { ConstraintFormulation::Sparse, ConstraintFormulation::MeanCentered })
    {
      const auto start = std::chrono::steady_clock::now();
      results.push_back(deform(bar, planarity, formulation, depth));
      const Result& r = results.back();
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double residual = maxDistance(r.constrained, projectToPlane(r.constrained));
      std::printf("%s, %s: planarity residual %.3g (unconstrained %.3g), %d iterations (%s, %.2f s), handle error %.3g, "
                  "fixed error %.3g\n",
        depth ? "Anderson" : "plain", formulation == ConstraintFormulation::Sparse ? "sparse" : "mean-centered", residual / diagonal,
        unconstrained / diagonal, r.solution.iterations, r.solution.converged ? "converged" : "not converged", seconds, r.handleError,
        r.fixedError);
      CHECK(r.solution.converged);
      checkKept(residual, unconstrained, r.handleError, r.fixedError, bar.motion.norm());
    }
  // The accelerated iteration reaches the plain one's answer, and both formulations have the same
  // fixed point (the sparse one by its deferred correction; before it they differed by 1.8e-3 of
  // the diagonal at gamma_c = 10 and 6.6e-3 at 1000).
  for (int f = 0; f < 2; ++f)
  {
    const double accelerated = maxDistance(results[2 + f].constrained, results[f].constrained) / diagonal;
    std::printf("accelerated vs plain: positions differ by %.2g of the diagonal\n", accelerated);
    CHECK(accelerated <= sameFixedPoint());
  }
  // A stiffer gamma_c converges more slowly (gamma_c = 1000 needs about 10^4 iterations), 100 is
  // run here.
  const double centeredAtTen = maxDistance(results[2].constrained, results[3].constrained) / diagonal;
  const Result sparseStiff = deform(bar, planarity, ConstraintFormulation::Sparse, 5, 100);
  const Result centeredStiff = deform(bar, planarity, ConstraintFormulation::MeanCentered, 5, 100);
  CHECK(sparseStiff.solution.converged && centeredStiff.solution.converged);
  const double centeredAtHundred = maxDistance(sparseStiff.constrained, centeredStiff.constrained) / diagonal;
  std::printf("sparse vs mean-centered: positions differ by %.2g (gamma_c = 10), %.2g (gamma_c = 100) of the diagonal\n",
    centeredAtTen, centeredAtHundred);
  CHECK(centeredAtTen <= sameFixedPoint());
  CHECK(centeredAtHundred <= sameFixedPoint());
  for (int f = 0; f < 2; ++f)
    CHECK(5 * results[2 + f].solution.iterations <= results[f].solution.iterations); // acceleration earns its place (Fig. 6 c: the requirement)
}

TEST(SparseFormulationStaysSparseForTheWholeMesh)
{
  // A planarity constraint on every point of a plane (section 6.1): mean-centering couples all
  // samples of the plane, the sparse formulation only neighbours and the pivot's samples (a
  // bounded number per row whatever k is).
  const SamplingDomain plane = testgeometry::triangulatedPlane(40, 40, 1, 1);
  SamplingParameters p;
  p.numberOfSurfaceSamples = 750;
  p.numberOfVolumeSamples = 250;
  const Samples samples = sampleDomain(plane, p);
  const MLSBasis basis(samples.centers, samples.supportRadius);
  const std::vector<ShapeConstraint> whole = { { ConstraintType::Planarity, plane.points, 1.0 } };
  const ShapeConstraints sparse(basis, whole, ConstraintFormulation::Sparse);
  const ShapeConstraints centered(basis, whole, ConstraintFormulation::MeanCentered);
  const double k = static_cast<double>(basis.size());
  const double sparseFill = sparse.normalMatrix().nonZeros() / (k * k), centeredFill = centered.normalMatrix().nonZeros() / (k * k);
  std::printf("fill of the k x k constraint matrix: sparse %.3f, mean-centered %.3f\n", sparseFill, centeredFill);
  // dense over the plane's samples: the 750 surface samples lie on the plane, so mean-centering
  // couples at least all of them, a fill of 0.75^2 = 0.56 or more
  CHECK(centeredFill > 0.5);
  // Sparse stays sparse, by its structure: row i of C Phi is phi(x_i) - phi(x_p) (p the pivot), so
  // (C Phi)^T (C Phi) couples two samples only if their supports overlap (|c_j - c_m| < r_j + r_m)
  // or one of them is among the pivot's samples (at most s_max, the most samples at any point of
  // the set): nnz <= overlapping pairs + 2 s_max k, a bounded number per row whatever k is.
  double overlapping = 0;
  for (std::size_t j = 0; j < basis.size(); ++j)
    for (std::size_t m = 0; m < basis.size(); ++m)
      overlapping += (samples.centers[j] - samples.centers[m]).norm() < basis.supportRadii()[j] + basis.supportRadii()[m];
  ShapeFunctionValues phi;
  std::size_t mostSamples = 0;
  for (const Vec3& x : plane.points)
  {
    basis.evaluate(x, phi, false);
    mostSamples = std::max(mostSamples, phi.index.size());
  }
  const double structural = overlapping + 2 * static_cast<double>(mostSamples) * k;
  std::printf("sparse non-zeros per row %.1f, structural bound %.1f (overlapping pairs %.1f per row, s_max %zu)\n",
    sparse.normalMatrix().nonZeros() / k, structural / k, overlapping / k, mostSamples);
  CHECK(sparse.normalMatrix().nonZeros() <= structural);
  CHECK(structural < centeredFill * k * k); // the bound itself is below the centered fill here
}

namespace
{
// Fig. 6 for one constraint type: the unconstrained deformation violates the constraint, the
// constrained one keeps it (a), meets the targets (b), and plain and accelerated iterations
// agree, the accelerated one in at least 5x fewer iterations (c).
void checkFigureSix(ConstraintType type, const PointList& set, const BentBar& bar, PointList (*violation)(const PointList& rest, const PointList& y))
{
  const Vec3& motion = bar.motion;
  const double diagonal = std::sqrt(11.0);
  const Result free = deform(bar, { { type, set, 0.0 } }, ConstraintFormulation::Sparse); // weight 0: unconstrained
  const double unconstrained = maxDistance(free.constrained, violation(set, free.constrained));
  const Result plain = deform(bar, { { type, set, 1.0 } }, ConstraintFormulation::Sparse, 0);
  const Result fast = deform(bar, { { type, set, 1.0 } }, ConstraintFormulation::Sparse, 5);
  for (const Result* r : { &plain, &fast })
  {
    const double residual = maxDistance(r->constrained, violation(set, r->constrained));
    std::printf("%s (%s): residual %.3g of the diagonal (unconstrained %.3g), %d iterations, handle error %.3g, fixed error %.3g\n",
      constraintName(type), r == &plain ? "plain" : "Anderson", residual / diagonal, unconstrained / diagonal, r->solution.iterations,
      r->handleError / motion.norm(), r->fixedError / motion.norm());
    CHECK(r->solution.converged);
    checkKept(residual, unconstrained, r->handleError, r->fixedError, motion.norm());
  }
  const double difference = maxDistance(plain.constrained, fast.constrained) / diagonal;
  std::printf("  plain vs Anderson: positions differ by %.2g of the diagonal, %d vs %d iterations\n", difference,
    plain.solution.iterations, fast.solution.iterations);
  CHECK(difference <= sameFixedPoint());
  CHECK(5 * fast.solution.iterations <= plain.solution.iterations); // acceleration earns its place

}

PointList onCircle(const Vec3& center, double radius, int count, double height = 0, int layers = 1)
{
  PointList x; // in the plane y = const around the y axis for layers > 1, else in z = const
  for (int l = 0; l < layers; ++l)
    for (int i = 0; i < count; ++i)
    {
      const double a = 2 * M_PI * i / count;
      x.push_back(layers > 1 ? center + Vec3(radius * std::cos(a), height * l / (layers - 1), radius * std::sin(a))
                             : center + Vec3(radius * std::cos(a), radius * std::sin(a), 0));
    }
  return x;
}
}

TEST(CircularityIsKept)
{
  // a ring on the top face, stretched along the bar
  checkFigureSix(ConstraintType::Circularity, onCircle(Vec3(1.5, 0.5, 1.0), 0.3, 32), BentBar(Vec3(0.6, 0, 0)),
    [](const PointList&, const PointList& y) { return projectToCircle(y); });
}

TEST(CylinderIsKept)
{
  // a cylinder across the bar (axis along y), stretched along the bar
  checkFigureSix(ConstraintType::Cylinder, onCircle(Vec3(1.5, 0.2, 0.5), 0.3, 24, 0.6, 5), BentBar(Vec3(0.3, 0, 0)),
    [](const PointList&, const PointList& y) {
      Vec3 axis = Vec3::Zero();
      return projectToCylinder(y, axis);
    });
}

TEST(FeatureLineIsKept)
{
  // a zig-zag line on the top face through the bent middle
  PointList line;
  for (int i = 0; i <= 20; ++i)
    line.push_back(Vec3(0.75 + 1.5 * i / 20.0, 0.5 + 0.2 * ((i % 4 < 2) ? 1 : -1), 1.0));
  checkFigureSix(ConstraintType::FeatureLine, line, BentBar(), &projectToSimilarity);
}

TEST(RigidIsKept)
{
  // a small block in the bent middle (e.g. boundary-layer cells kept rigid)
  PointList block;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        block.push_back(Vec3(1.05 + 0.15 * i, 0.35 + 0.15 * j, 0.35 + 0.15 * k));
  // a block this small needs a finer subspace to stay rigid while the bar bends around it
  checkFigureSix(ConstraintType::Rigid, block, BentBar(Vec3(0, 0, 0.5), 600, 300), &projectToRigid);
}

namespace
{
bool bitwiseEqual(const Displacements& a, const Displacements& b)
{
  return a.rows() == b.rows() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

bool bitwiseEqual(const PointList& a, const PointList& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(Vec3) * a.size()) == 0;
}

// A cylinder across the bar and a plane on its top: both projections, one of them iterative.
std::vector<ShapeConstraint> cylinderAndPlane(const BentBar& bar)
{
  return { { ConstraintType::Cylinder, onCircle(Vec3(1.5, 0.2, 0.5), 0.3, 24, 0.6, 5), 1.0 },
    { ConstraintType::Planarity, bar.select([](const Vec3& x) { return x.z() > 1 - 1e-9 && x.x() > 0.5 - 1e-9 && x.x() < 1.25 + 1e-9; }), 1.0 } };
}
}

TEST(SameAnswerOnOneAndTwoThreads)
{
  // Sampling, operators, factorization and the constraint iteration, bitwise: every parallel
  // loop writes each result entry from one thread in a fixed order, Gram matrices are summed
  // over row chunks of a fixed size, and CHOLMOD's BLAS runs on one thread (SparseCholesky.h).
  struct Run
  {
    Samples samples;
    Displacements w;
    int iterations = 0;
  };
  std::vector<Run> runs;
  const int threads = omp_get_max_threads();
  for (int t : { 1, 2 })
  {
    omp_set_num_threads(t);
    const BentBar bar(Vec3(0.3, 0, 0.3));
    const Result r = deform(bar, cylinderAndPlane(bar), ConstraintFormulation::Sparse);
    runs.push_back({ bar.samples, r.solution.w, r.solution.iterations });
  }
  omp_set_num_threads(threads);
  std::printf("iterations: %d (1 thread), %d (2 threads)\n", runs[0].iterations, runs[1].iterations);
  CHECK(bitwiseEqual(runs[0].samples.centers, runs[1].samples.centers));
  CHECK(bitwiseEqual(runs[0].samples.integrationPoints, runs[1].samples.integrationPoints));
  CHECK(runs[0].samples.supportRadius == runs[1].samples.supportRadius && runs[0].samples.volume == runs[1].samples.volume);
  CHECK(runs[0].iterations == runs[1].iterations);
  CHECK(bitwiseEqual(runs[0].w, runs[1].w));
}

TEST(AnswerDependsOnItsInputsOnly)
{
  // Two handle motions solved in either order on one set-up give the same answers, bitwise: the
  // iteration keeps no state between solves (the cylinder fit starts from the rest axis).
  const BentBar bar;
  SpaceDeformation model(bar.samples);
  model.setRegions(bar.regions);
  model.setConstraints(cylinderAndPlane(bar), ConstraintFormulation::Sparse);
  model.factorize(EnergyWeights{});
  auto motion = [&](const Vec3& handle) {
    return std::vector<PointDisplacements>{ handle.transpose().replicate(bar.regions[0].positions.size(), 1),
      PointDisplacements::Zero(bar.regions[1].positions.size(), 3) };
  };
  const auto a = motion(Vec3(0.3, 0, 0.2)), b = motion(Vec3(-0.2, 0.1, 0.4));
  const Displacements a1 = model.solve(a).w, b1 = model.solve(b).w;
  const Displacements b2 = model.solve(b).w, a2 = model.solve(a).w;
  CHECK(bitwiseEqual(a1, a2));
  CHECK(bitwiseEqual(b1, b2));
  CHECK(!bitwiseEqual(a1, b1));
}

TEST_MAIN
