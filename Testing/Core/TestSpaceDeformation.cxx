// Section 5, eq. 12-14: invariants of the solve.
#include "SpaceDeformation.h"
#include "SubspaceOperators.h"
#include "TestGeometry.h"
#include "../TestHarness.h"

using namespace mlsdeform;

namespace
{
struct Scene
{
  SamplingDomain box = testgeometry::tetrahedralBox(6, Vec3(3, 1, 1));
  Samples samples;
  std::vector<DirichletRegion> regions; // 0: handle x = 3, 1: fixed x = 0
  Scene()
  {
    SamplingParameters p;
    p.numberOfSurfaceSamples = 200;
    p.numberOfVolumeSamples = 100;
    p.lloydIterations = 5;
    samples = sampleDomain(box, p);
    regions.resize(2);
    for (const Vec3& x : box.points)
    {
      if (x.x() > 3 - 1e-9)
        regions[0].positions.push_back(x);
      if (x.x() < 1e-9)
        regions[1].positions.push_back(x);
    }
  }
  std::vector<Displacements> uniform(const Vec3& handle, const Vec3& fixed) const
  {
    std::vector<Displacements> d(2);
    d[0] = handle.transpose().replicate(regions[0].positions.size(), 1);
    d[1] = fixed.transpose().replicate(regions[1].positions.size(), 1);
    return d;
  }
};

Displacements evaluate(const SpaceDeformation& model, const Displacements& w, const PointList& x)
{
  return subspaceMatrix(model.basis(), x) * w;
}
}

TEST(CommonTranslationMovesEveryPointByIt)
{
  Scene scene;
  for (const EnergyWeights& weights : { EnergyWeights{ 1, 0, 1000 }, EnergyWeights{ 0, 1, 1000 }, EnergyWeights{ 1, 0.6, 100 } })
  {
    SpaceDeformation model(scene.samples);
    model.setRegions(scene.regions);
    model.factorize(weights);
    const Vec3 t(0.3, -0.2, 0.5);
    const Displacements w = model.solve(scene.uniform(t, t)).w;
    const Displacements d = evaluate(model, w, scene.box.points);
    const double error = (d.rowwise() - t.transpose()).rowwise().norm().maxCoeff() / t.norm();
    std::printf("gamma_s %g gamma_b %g: max relative error %g, rcond %g\n", weights.stretch, weights.bend, error, model.reciprocalCondition());
    CHECK(error <= 1e-8);
  }
}

TEST(OnlyFixedRegionsMoveNothing)
{
  Scene scene;
  SpaceDeformation model(scene.samples);
  model.setRegions(scene.regions);
  model.factorize(EnergyWeights{});
  const Displacements w = model.solve(scene.uniform(Vec3::Zero(), Vec3::Zero())).w;
  CHECK(evaluate(model, w, scene.box.points).cwiseAbs().maxCoeff() == 0.0);
}

TEST(HandleAndFixedTargetsAreMet)
{
  Scene scene;
  SpaceDeformation model(scene.samples);
  model.setRegions(scene.regions);
  model.factorize(EnergyWeights{ 0, 1, 1000 });
  const Vec3 lift(0, 0, 0.5);
  const auto prescribed = scene.uniform(lift, Vec3::Zero());
  const SpaceDeformation::Solution solution = model.solve(prescribed);
  const Displacements& w = solution.w;
  // the residuals from the quadratic forms equal those measured at the region points
  for (int r = 0; r < 2; ++r)
  {
    const Displacements d = evaluate(model, w, scene.regions[r].positions);
    const double measured = std::sqrt((d - prescribed[r]).squaredNorm() / d.rows());
    std::printf("region %d: rms residual %g, measured %g (of %g)\n", r, solution.rmsResidual[r], measured, lift.norm());
    CHECK_NEAR(solution.rmsResidual[r], measured, 1e-6 * lift.norm());
    CHECK((d - prescribed[r]).rowwise().norm().maxCoeff() <= 0.01 * lift.norm());
  }
  // the middle moves part of the way, monotonically along the bar
  const Displacements d = evaluate(model, w, { Vec3(0.75, 0.5, 0.5), Vec3(1.5, 0.5, 0.5), Vec3(2.25, 0.5, 0.5) });
  CHECK(0 < d(0, 2) && d(0, 2) < d(1, 2) && d(1, 2) < d(2, 2) && d(2, 2) < 0.5);
}

TEST(SingularSystemIsReported)
{
  Scene scene;
  SpaceDeformation model(scene.samples);
  model.setRegions(scene.regions);
  CHECK_THROWS(model.factorize(EnergyWeights{ 0, 0, 1000 }), SolverException);
  CHECK_THROWS(model.solve(scene.uniform(Vec3::Zero(), Vec3::Zero())), SolverException);
}

TEST(BadRegionsAreRejected)
{
  Scene scene;
  SpaceDeformation model(scene.samples);
  std::vector<DirichletRegion> regions = scene.regions;
  regions[1].positions.clear();
  CHECK_THROWS(model.setRegions(regions), InvalidInputException);
  regions[1].positions = { Vec3(100, 0, 0) };
  CHECK_THROWS(model.setRegions(regions), InvalidInputException);
  regions[1].positions = { Vec3(0, std::nan(""), 0) };
  CHECK_THROWS(model.setRegions(regions), InvalidInputException);
}

TEST_MAIN
