// Set-up time, per-variation time and peak memory of vtkMLSDeformFilter on a generated closed
// surface (a sphere tessellated to the requested number of points): bottom cap fixed, top cap
// moved. One configuration per process so that the peak memory is that configuration's.
// Variations alternate between 1 and 2 OpenMP threads on the same set-up, so that both figures
// come from the same run, side by side; page faults per variation show whether a variation
// still touches fresh memory (mesh-sized allocations would fault on every page).
// Fails (exit code 1) when a figure it prints is not finite or absurd, or the handle misses its
// target by more than the penalty balance allows, so that the smoke run (Benchmarks.Smoke)
// checks what it prints.
// Usage: BenchmarkDeformation POINTS K [VARIATIONS per thread count]; prints one JSON line.
#include "vtkConstraintRegion.h"
#include "vtkMLSDeformFilter.h"

#include <vtkBox.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace
{
double peakMemoryMiB()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0)
      return std::stod(line.substr(6)) / 1024.0;
  return -1;
}

long minorPageFaults()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values.empty() ? 0 : values[values.size() / 2];
}

double seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double field(vtkMLSDeformFilter* deform, const char* name)
{
  return deform->GetOutputDataObject(0)->GetFieldData()->GetArray(name)->GetTuple1(0);
}

// The largest RMS misfit of the handle for a motion of this length: what pulls the handle off its
// target is at most StretchWeight + BendWeight against FixWeight (eq. 12-14), so its RMS misfit
// stays below that ratio of the motion (the bound of Testing/Python/test_proxies.py).
double handleResidualBound(vtkMLSDeformFilter* deform, double motion)
{
  return (deform->GetStretchWeight() + deform->GetBendWeight()) / deform->GetFixWeight() * motion;
}

// A figure outside its range fails the run (after the JSON line).
bool failed = false;
void require(bool ok, const char* what)
{
  if (!ok)
  {
    std::fprintf(stderr, "failed: %s\n", what);
    failed = true;
  }
}
}

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr, "usage: %s POINTS K [VARIATIONS]\n", argv[0]);
    return 2;
  }
  const long points = std::atol(argv[1]);
  const int k = std::atoi(argv[2]);
  const int variations = argc > 3 ? std::atoi(argv[3]) : 7;

  // A UV sphere has theta * (phi - 2) + 2 points.
  const int resolution = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(points))));
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution + 2);
  sphere->Update();
  vtkPolyData* surface = sphere->GetOutput();

  vtkNew<vtkBox> bottom, top;
  bottom->SetBounds(-2, 2, -2, 2, -2, -0.8);
  top->SetBounds(-2, 2, -2, 2, 0.8, 2);
  vtkNew<vtkConstraintRegion> fixed, handle;
  fixed->SetInputData(surface);
  fixed->SetRole(vtkConstraintRegion::Fixed);
  fixed->SetRegion(bottom);
  handle->SetInputData(surface);
  handle->SetRegion(top);
  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputData(surface);
  deform->AddRegionConnection(fixed->GetOutputPort());
  deform->AddRegionConnection(handle->GetOutputPort());
  deform->SetNumberOfSamples(k);

  auto start = std::chrono::steady_clock::now();
  handle->SetTranslation(0.1, 0, 0.2);
  deform->Update();
  const double setup = seconds(start);
  if (!deform->GetOutputDataObject(0)->GetFieldData()->GetArray("SetupTime"))
  {
    std::fprintf(stderr, "the deformation failed\n");
    return 1;
  }
  const double integrationPoints = field(deform, "NumberOfIntegrationPoints");
  require(field(deform, "HandleResidual") <= handleResidualBound(deform, std::hypot(0.1, 0.2)), "the handle reaches its target at set-up");

  // Variations: new handle motion only (regions re-executed, then solve and evaluation),
  // alternately on 1 and 2 threads.
  const int threadCounts[2] = { 1, 2 };
  std::vector<double> times[2], faults;
  for (int v = 0; v < 2 * variations; ++v)
  {
    const int t = v % 2;
    omp_set_num_threads(threadCounts[t]);
    const double translation[3] = { 0.1, 0.02 * (v + 1), 0.2 + 0.01 * (v + 1) };
    handle->SetTranslation(translation);
    const long faultsBefore = minorPageFaults();
    start = std::chrono::steady_clock::now();
    handle->Update();
    const double region = seconds(start);
    deform->Update();
    times[t].push_back(seconds(start));
    faults.push_back(static_cast<double>(minorPageFaults() - faultsBefore));
    const double handleResidual = field(deform, "HandleResidual");
    const double bound = handleResidualBound(deform, std::hypot(translation[0], translation[1], translation[2]));
    std::fprintf(stderr,
      "variation %d, %d thread(s): region %.1f ms, filter %.1f ms (solve+evaluate %.1f ms), %.0f page faults, handle residual %.2g (bound %.2g)\n",
      v, threadCounts[t], 1000 * region, 1000 * (times[t].back() - region), 1000 * field(deform, "SolveTime"), faults.back(),
      handleResidual, bound);
    require(handleResidual <= bound, "the handle reaches its target in every variation");
  }
  const bool cached = deform->GetNumberOfSamplings() == 1 && deform->GetNumberOfFactorizations() == 1;
  std::printf("{\"points\": %lld, \"k\": %d, \"N\": %.0f, \"setup_s\": %.3f, \"variation_median_ms_1_thread\": %.1f, "
              "\"variation_median_ms_2_threads\": %.1f, \"page_faults_per_variation\": %.0f, \"variations\": %d, "
              "\"peak_memory_MiB\": %.0f, \"cached\": %s}\n",
    static_cast<long long>(surface->GetNumberOfPoints()), k, integrationPoints, setup, 1000 * median(times[0]), 1000 * median(times[1]),
    median(faults), variations, peakMemoryMiB(), cached ? "true" : "false");
  require(cached, "the variations reuse the sampling and the factorization");
  require(integrationPoints > 0, "integration points");
  require(std::isfinite(setup) && setup > 0, "a finite set-up time");
  require(std::isfinite(median(times[0])) && std::isfinite(median(times[1])), "finite variation times");
  require(peakMemoryMiB() > 0, "the peak memory is known");
  return failed ? 1 : 0;
}
