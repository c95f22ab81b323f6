// Primitive detection (paper section 6.3) against CGAL's Efficient RANSAC on the same oriented
// face samples (barycenters and face normals): time and coverage (fraction of the faces that
// belong to a primitive) on CGAL's parts (fandisk and joint, or the ones named) and on a generated
// part of about 100k faces, clean and with noise of 0.1% of the diagonal. Same epsilon, cluster
// epsilon, normal threshold, minimum support and probability (CGAL's is the probability of
// missing a shape: 1 - ours). Each line is a JSON record with the medians of the runs (run r
// uses seed r for both) and the least coverage of any run.
//
//   BenchmarkPrimitiveDetection DATA_DIR [runs [PART...]]
//
// CGAL's Shape_detection is GPL: this program is a benchmark only, built when CMake is given
// -DMLSDEFORM_BENCHMARK_CGAL=ON, and never linked into the plugin.
#include "Primitives/EfficientRansac.h"
#include "Primitives/FaceSamples.h"
#include "Sampling/Sampling.h"
#include "SyntheticParts.h"
#include "vtkOFFReader.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Shape_detection/Efficient_RANSAC.h>

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using PointWithNormal = std::pair<Kernel::Point_3, Kernel::Vector_3>;
using Samples = std::vector<PointWithNormal>;
using Traits = CGAL::Shape_detection::Efficient_RANSAC_traits<Kernel, Samples, CGAL::First_of_pair_property_map<PointWithNormal>,
  CGAL::Second_of_pair_property_map<PointWithNormal>>;
using CgalRansac = CGAL::Shape_detection::Efficient_RANSAC<Traits>;

struct Mesh
{
  std::string name;
  mlsdeform::PointList points;
  std::vector<std::vector<int>> faces;
};

Mesh readOFF(const std::string& directory, const std::string& name)
{
  vtkNew<vtkOFFReader> reader;
  reader->SetFileName((directory + "/" + name + ".off").c_str());
  reader->Update();
  vtkPolyData* surface = reader->GetOutput();
  Mesh mesh{ name, {}, {} };
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
    mesh.points.emplace_back(surface->GetPoint(i));
  auto iterator = vtk::TakeSmartPointer(surface->GetPolys()->NewIterator());
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    iterator->GetCurrentCell(size, ids);
    mesh.faces.emplace_back(ids, ids + size);
  }
  return mesh;
}

double seconds(const std::chrono::steady_clock::time_point& start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void compare(const Mesh& mesh, int runs)
{
  const mlsdeform::FaceSamples samples = mlsdeform::faceSamples(mesh.points, mesh.faces);
  mlsdeform::PointList points;
  std::vector<mlsdeform::Vec3> normals;
  mlsdeform::SampleFaces faces; // of the samples
  faces.vertices = mesh.points;
  Samples cgalSamples;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
  {
    if (!samples.normals[f].allFinite())
      continue; // degenerate faces are no samples for either
    points.push_back(samples.barycenters[f]);
    normals.push_back(samples.normals[f]);
    faces.faces.push_back(mesh.faces[f]);
    const mlsdeform::Vec3& p = samples.barycenters[f];
    const mlsdeform::Vec3& n = samples.normals[f];
    cgalSamples.emplace_back(Kernel::Point_3(p.x(), p.y(), p.z()), Kernel::Vector_3(n.x(), n.y(), n.z()));
  }
  const double diagonal = mlsdeform::boundingBox(mesh.points).size().norm();
  // the detector's defaults (vtkPrimitiveDetector)
  mlsdeform::RansacParameters ours;
  ours.epsilon = 0.005 * diagonal;
  ours.clusterEpsilon = 0.02 * diagonal;
  ours.normalThreshold = 20 * M_PI / 180;
  ours.minimumSupport = 10;
  ours.probability = 0.95;
  CgalRansac::Parameters theirs;
  theirs.epsilon = ours.epsilon;
  theirs.cluster_epsilon = ours.clusterEpsilon;
  theirs.normal_threshold = std::cos(ours.normalThreshold);
  theirs.min_points = static_cast<std::size_t>(ours.minimumSupport);
  theirs.probability = 1 - ours.probability;

  std::vector<double> ourTimes, cgalTimes, ourCoverage, cgalCoverage, ourCount, cgalCount;
  for (int run = 0; run < runs; ++run)
  {
    ours.seed = static_cast<std::uint64_t>(run);
    auto start = std::chrono::steady_clock::now();
    const std::vector<mlsdeform::DetectedPrimitive> found = mlsdeform::detectPrimitives(points, normals, ours, &faces);
    ourTimes.push_back(seconds(start));
    std::size_t covered = 0;
    for (const auto& p : found)
      covered += p.members.size();
    ourCoverage.push_back(static_cast<double>(covered) / mesh.faces.size());
    ourCount.push_back(static_cast<double>(found.size()));

    Samples input = cgalSamples;
    CGAL::get_default_random() = CGAL::Random(static_cast<unsigned>(run));
    start = std::chrono::steady_clock::now();
    CgalRansac ransac;
    ransac.set_input(input);
    ransac.add_shape_factory<CGAL::Shape_detection::Plane<Traits>>();
    ransac.add_shape_factory<CGAL::Shape_detection::Cylinder<Traits>>();
    ransac.add_shape_factory<CGAL::Shape_detection::Sphere<Traits>>();
    ransac.add_shape_factory<CGAL::Shape_detection::Cone<Traits>>();
    ransac.detect(theirs);
    cgalTimes.push_back(seconds(start));
    covered = 0;
    for (const auto& shape : ransac.shapes())
      covered += shape->indices_of_assigned_points().size();
    cgalCoverage.push_back(static_cast<double>(covered) / mesh.faces.size());
    cgalCount.push_back(static_cast<double>(ransac.shapes().size()));
  }
  std::printf("{\"mesh\": \"%s\", \"faces\": %zu, \"runs\": %d, \"ours_seconds\": %.4f, \"cgal_seconds\": %.4f, "
              "\"ours_coverage\": %.4f, \"cgal_coverage\": %.4f, \"ours_coverage_least\": %.4f, \"cgal_coverage_least\": %.4f, "
              "\"ours_primitives\": %.0f, \"cgal_primitives\": %.0f}\n",
    mesh.name.c_str(), mesh.faces.size(), runs, median(ourTimes), median(cgalTimes), median(ourCoverage), median(cgalCoverage),
    *std::min_element(ourCoverage.begin(), ourCoverage.end()), *std::min_element(cgalCoverage.begin(), cgalCoverage.end()),
    median(ourCount), median(cgalCount));
  std::fflush(stdout);
}

Mesh generated(bool noisy)
{
  syntheticparts::Part part = syntheticparts::blockWithFeatures(0.03, 96);
  if (noisy)
    syntheticparts::addNoise(part, 0.001 * part.diagonal() / std::sqrt(3.0), 1);
  return { noisy ? "part100k_noisy" : "part100k", part.points, part.faces };
}
}

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::printf("usage: %s DATA_DIR [runs [PART...]] (PART: an OFF file of DATA_DIR without .off; default fandisk joint)\n", argv[0]);
    return 2;
  }
  const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 15;
  std::vector<std::string> parts(argv + std::min(argc, 3), argv + argc);
  if (parts.empty())
    parts = { "fandisk", "joint" };
  for (const std::string& part : parts)
    compare(readOFF(argv[1], part), runs);
  compare(generated(false), runs);
  compare(generated(true), runs);
  return 0;
}
