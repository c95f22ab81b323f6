// Section 6: the local/global iteration keeps geometric constraints during the deformation.
#include "../TestHarness.h"
#include "ConstraintProjections.h"
#include "SpaceDeformation.h"
#include "SubspaceOperators.h"
#include "TestGeometry.h"

#include <chrono>

using namespace mlsdeform;

namespace
{
// The bar [0,3] x [0,1] x [0,1], clamped: fixed for x <= 0.5, handle x >= 2.5 lifted by 0.5, so
// that the middle bends (S-shaped).
struct BentBar
{
  SamplingDomain box = testgeometry::tetrahedralBox(12, Vec3(3, 1, 1));
  Samples samples;
  std::vector<DirichletRegion> regions;
  std::vector<Displacements> prescribed;
  BentBar()
  {
    SamplingParameters p;
    p.numberOfSurfaceSamples = 300;
    p.numberOfVolumeSamples = 100;
    samples = sampleDomain(box, p);
    regions.resize(2);
    for (const Vec3& x : box.points)
    {
      if (x.x() > 2.5 - 1e-9)
        regions[0].positions.push_back(x);
      if (x.x() < 0.5 + 1e-9)
        regions[1].positions.push_back(x);
    }
    prescribed = { Vec3(0, 0, 0.5).transpose().replicate(regions[0].positions.size(), 1),
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
    result.handleError = std::max(result.handleError, (handle[i] - bar.regions[0].positions[i] - Vec3(0, 0, 0.5)).norm());
  for (std::size_t i = 0; i < fixed.size(); ++i)
    result.fixedError = std::max(result.fixedError, (fixed[i] - bar.regions[1].positions[i]).norm());
  return result;
}

double maxDistance(const PointList& a, const PointList& b)
{
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    d = std::max(d, (a[i] - b[i]).norm());
  return d;
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
      CHECK(residual <= 1e-3 * diagonal);
      CHECK(residual <= 0.1 * unconstrained);
      CHECK(r.handleError <= 0.02 * 0.5 && r.fixedError <= 0.02 * 0.5);
    }
  // the accelerated iteration reaches the plain one's answer
  for (int f = 0; f < 2; ++f)
  {
    const double accelerated = maxDistance(results[2 + f].constrained, results[f].constrained) / diagonal;
    std::printf("accelerated vs plain: positions differ by %.2g of the diagonal\n", accelerated);
    CHECK(accelerated <= 1e-4);
  }
  // The soft constraint is measured about the mean (eq. 16) or about one point (section 6.1),
  // so at a finite gamma_c the formulations settle slightly differently (e.g. the plane's tilt);
  // the difference shrinks as gamma_c grows (measured: 1.8e-3 at 10, 8.7e-4 at 100).
  const double atTen = maxDistance(results[2].constrained, results[3].constrained) / diagonal;
  const double atHundred = maxDistance(deform(bar, planarity, ConstraintFormulation::Sparse, 5, 100).constrained,
                             deform(bar, planarity, ConstraintFormulation::MeanCentered, 5, 100).constrained) / diagonal;
  std::printf("sparse vs mean-centered: positions differ by %.2g (gamma_c = 10), %.2g (gamma_c = 100) of the diagonal\n", atTen, atHundred);
  CHECK(atTen <= 2.5e-3);
  CHECK(atHundred <= 0.6 * atTen);
  for (int f = 0; f < 2; ++f)
    CHECK(5 * results[2 + f].solution.iterations <= results[f].solution.iterations);
}

TEST_MAIN
