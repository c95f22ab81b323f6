// Per-iteration cost of the constrained deformation (paper section 6) at k = 4000 samples: a
// plane of 160k points bent between a fixed and a lifted strip, a planarity constraint on n
// points of the bent middle. Prints one JSON line per n and iteration kind; fails (exit code 1)
// when an iteration did not converge or its residual is not finite, so that the smoke run
// (Benchmarks.ConstraintsSmoke) checks what it prints.
// Usage: BenchmarkConstraints [K] [N1 N2 ...]
#include "Solver/SpaceDeformation.h"
#include "../Core/TestGeometry.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

using namespace mlsdeform;

int main(int argc, char* argv[])
{
  const int k = argc > 1 ? std::atoi(argv[1]) : 4000;
  std::vector<int> counts;
  for (int a = 2; a < argc; ++a)
    counts.push_back(std::atoi(argv[a]));
  if (counts.empty())
    counts = { 1000, 10000, 100000 };

  const SamplingDomain plane = testgeometry::triangulatedPlane(400, 400, 1, 1);
  SamplingParameters p;
  p.numberOfSurfaceSamples = k * 3 / 4;
  p.numberOfVolumeSamples = k - p.numberOfSurfaceSamples;
  const Samples samples = sampleDomain(plane, p);
  std::vector<DirichletRegion> regions(2);
  PointList middle;
  for (const Vec3& x : plane.points)
  {
    if (x.x() > 0.9)
      regions[0].positions.push_back(x);
    else if (x.x() < 0.1)
      regions[1].positions.push_back(x);
    else if (x.x() > 0.12 && x.x() < 0.88)
      middle.push_back(x);
  }
  std::shuffle(middle.begin(), middle.end(), std::mt19937(1));
  const std::vector<PointDisplacements> prescribed = { Vec3(0, 0, 0.3).transpose().replicate(regions[0].positions.size(), 1),
    Displacements::Zero(regions[1].positions.size(), 3) };

  bool failed = false;
  for (int n : counts)
  {
    const PointList set(middle.begin(), middle.begin() + std::min<std::size_t>(n, middle.size()));
    SpaceDeformation model(samples);
    model.setRegions(regions);
    auto start = std::chrono::steady_clock::now();
    model.setConstraints({ { ConstraintType::Planarity, set, 1.0 } }, ConstraintFormulation::Sparse);
    model.factorize(EnergyWeights{});
    const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (int depth : { 0, 5 })
    {
      IterationSettings settings;
      settings.andersonDepth = depth;
      start = std::chrono::steady_clock::now();
      const SpaceDeformation::Solution s = model.solve(prescribed, settings);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("{\"k\": %zu, \"constrained_points\": %zu, \"acceleration\": \"%s\", \"iterations\": %d, \"converged\": %s, "
                  "\"solve_s\": %.3f, \"per_iteration_ms\": %.2f, \"residual\": %.2e, \"constraint_setup_s\": %.2f}\n",
        model.basis().size(), set.size(), depth ? "Anderson" : "None", s.iterations, s.converged ? "true" : "false", seconds,
        1000 * seconds / std::max(1, s.iterations), s.constraintResidual[0], setup);
      std::fflush(stdout);
      if (!s.converged || !std::isfinite(s.constraintResidual[0]))
      {
        std::fprintf(stderr, "n = %d, %s: the iteration did not converge to a finite residual\n", n, depth ? "Anderson" : "None");
        failed = true;
      }
    }
  }
  return failed ? 1 : 0;
}
