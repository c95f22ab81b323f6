// Placement of MLS samples and integration points (paper Fig. 2 and section 5): dense random
// samples on the surface and in the volume, farthest-point selection, Lloyd relaxation with the
// surface weighted more than the volume, support radii from the cover s, and approximate Voronoi
// volumes of the integration points.
#pragma once

#include "Common/BoundingBox.h"
#include "Common/SamplingDomain.h"

#include <array>
#include <cstdint>

namespace mlsdeform
{
struct SamplingParameters
{
  int numberOfSurfaceSamples = 800; // k_s
  int numberOfVolumeSamples = 200;  // k_v
  double integrationPointRatio = 4;  // N / k
  int lloydIterations = 5;
  double cover = 5;                  // s: every sampled position lies in at least s supports
  std::uint64_t randomSeed = 0;
  double surfaceWeight = 10;         // weight of a dense surface sample in the Lloyd step (volume: 1)
  int denseSamplesPerSample = 10;    // dense random samples per selected sample or point
  double boundsPadding = 0.1;        // fraction of the bounding-box diagonal, for surface-only input
  // Samples follow the mesh's own grading: every triangle and tetrahedron draws as many dense
  // samples (instead of as many per area or volume), and the farthest-point selection measures
  // distances in units of the local element size, so sample density follows element density
  // (a snappyHexMesh case: dense at the refined body, sparse at the far field). Off: uniform in
  // area and volume, as in the paper's CAD examples.
  bool followMeshGrading = true;

  /// Every parameter above, in order: the key of a sampling (two samplings with equal keys are
  /// the same). A parameter added above must be added here.
  std::vector<double> key() const
  {
    return { static_cast<double>(numberOfSurfaceSamples), static_cast<double>(numberOfVolumeSamples), integrationPointRatio,
      static_cast<double>(lloydIterations), cover, static_cast<double>(randomSeed), surfaceWeight,
      static_cast<double>(denseSamplesPerSample), boundsPadding, followMeshGrading ? 1.0 : 0.0 };
  }
};

struct Samples
{
  PointList centers;                // MLS samples c_j, surface samples first
  std::vector<double> supportRadius; // sigma_j
  int numberOfSurfaceCenters = 0;
  PointList integrationPoints;      // q_i
  std::vector<double> volume;       // V_i, approximate Voronoi volume within the domain
  double domainVolume = 0;          // volume of the embedding space that was sampled
};

/// The whole sampling of Fig. 2 / section 5. Throws InvalidInputException on empty or
/// non-finite input and on a domain of zero extent. A domain split over the processes of group
/// (each holding its own elements and points) gives every process the samples of the whole
/// domain, the same as sampling it whole on one process: dense samples are drawn per element from
/// random numbers keyed by its vertices' positions and sorted, so that neither the order nor the
/// split of the elements matters. Throws AbortedException when progress asks to stop (a
/// request that every process must make alike under MPI).
Samples sampleDomain(const SamplingDomain& domain, const SamplingParameters& parameters, const Progress& progress = {},
  const Collective& group = serial());

/// Farthest-point selection of up to count indices of candidates, starting from the points
/// already chosen (or from a random candidate): each step takes the candidate farthest from the
/// chosen ones in units of its spacing (distance / spacing[i]; empty spacing: 1, plain
/// distance), so that selected points lie about as far apart as their spacing says. Stops early
/// when only duplicates remain. Throws AbortedException when progress asks to stop.
std::vector<int> farthestPointSelection(const PointList& candidates, int count, const PointList& alreadyChosen, std::uint64_t seed,
  const std::vector<double>& spacing = {}, const Progress& progress = {});

/// Weighted Lloyd relaxation: each site moves to the weighted barycenter of the dense points
/// closest to it. Throws AbortedException when progress asks to stop.
void lloydRelaxation(PointList& sites, const PointList& dense, const std::vector<double>& denseWeight, int iterations,
  const Progress& progress = {});

/// Support radii following the local sample density (the distance to the s-th nearest fellow
/// sample, and at least to the s-th nearest of the measured points: the integration points the
/// energies are measured at, those with a volume), enlarged so that each of the positions lies
/// within reach of at least s samples (its s nearest grow, or on a graded volume mesh those that
/// grow least relative to their reach); a margin makes the weight at the reach w(1/margin) = 0.25.
/// The positions may be split over the processes of group (centers and measured points are the
/// same on all).
std::vector<double> coverSupportRadii(const PointList& centers, const std::vector<const PointList*>& positions, double cover,
  bool volumeMesh = false, const PointList& measured = {}, const Collective& group = serial());

} // namespace mlsdeform
