// Set-up time, per-variation time and peak memory of vtkMLSDeformFilter on a generated closed
// surface (a sphere tessellated to the requested number of points): bottom cap fixed, top cap
// moved. One configuration per process so that the peak memory is that configuration's.
// Usage: BenchmarkDeformation POINTS K [VARIATIONS]; prints one JSON line.
#include "vtkConstraintRegion.h"
#include "vtkMLSDeformFilter.h"

#include <vtkBox.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

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

double seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  vtkFieldData* field = deform->GetOutputDataObject(0)->GetFieldData();
  if (!field->GetArray("SetupTime"))
  {
    std::fprintf(stderr, "the deformation failed\n");
    return 1;
  }
  const double integrationPoints = field->GetArray("NumberOfIntegrationPoints")->GetTuple1(0);

  // Variations: new handle motion only (regions re-executed, then solve and evaluation).
  std::vector<double> times;
  for (int v = 0; v < variations; ++v)
  {
    handle->SetTranslation(0.1, 0.02 * v, 0.2 + 0.01 * v);
    start = std::chrono::steady_clock::now();
    handle->Update();
    const double region = seconds(start);
    deform->Update();
    times.push_back(seconds(start));
    std::fprintf(stderr, "variation %d: region %.1f ms, filter %.1f ms (solve+evaluate %.1f ms)\n", v, 1000 * region,
      1000 * (times.back() - region), 1000 * deform->GetOutputDataObject(0)->GetFieldData()->GetArray("SolveTime")->GetTuple1(0));
  }
  std::sort(times.begin(), times.end());
  const double median = times.empty() ? 0 : times[times.size() / 2];
  const bool cached = deform->GetNumberOfSamplings() == 1 && deform->GetNumberOfFactorizations() == 1;
  std::printf("{\"points\": %lld, \"k\": %d, \"N\": %.0f, \"setup_s\": %.3f, \"variation_median_ms\": %.1f, "
              "\"variations\": %d, \"peak_memory_MiB\": %.0f, \"cached\": %s}\n",
    static_cast<long long>(surface->GetNumberOfPoints()), k, integrationPoints, setup, 1000 * median, variations, peakMemoryMiB(),
    cached ? "true" : "false");
  return cached ? 0 : 1;
}
