#include "Sampling.h"

#include "KdTree.h"
#include "ZOrder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <random>

namespace mlsdeform
{
namespace
{
// A position's s-th nearest center lies at 1/SupportMargin of that center's radius, where its
// weight is w = 1/2 cos(pi / 1.5) + 1/2 = 0.25.
constexpr double SupportMargin = 1.5;
// Sample reaches that differ by more than this factor (10th to 90th percentile) come from a
// graded mesh (coverSupportRadii).
constexpr double GradedSpread = 2;

// Dense random samples, each with the size of the element it was drawn from (its spacing, for
// the farthest-point selection) and, in the volume, its share of the domain's volume.
struct DenseSamples
{
  PointList surface;
  std::vector<double> surfaceSpacing;
  PointList volume;
  std::vector<double> volumeSpacing;
  std::vector<double> volumeShare; // sums to volumeOfDomain
  double volumeOfDomain = 0;
};

double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c)
{
  return 0.5 * (b - a).cross(c - a).norm();
}

double tetrahedronVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return std::abs((b - a).dot((c - a).cross(d - a))) / 6.0;
}

// Draws `count` elements of dimension `dimension` (2: triangles, 3: tetrahedra), each with
// probability proportional to its measure, or, following the grading, the same for every element
// of positive measure; each drawn point gets the spacing measure^(1/dimension) of its element (1
// when uniform) and an importance weight measure / probability, scaled so that the weights sum
// to the total measure (a Monte Carlo estimate of the measure nearest to each point).
template <typename Measure, typename Draw>
void sampleElements(std::size_t elements, int count, int dimension, bool followGrading, Measure measure, Draw draw,
  std::mt19937_64& random, PointList& out, std::vector<double>& spacing, std::vector<double>* share, double& total)
{
  std::vector<double> measures(elements), cumulative(elements);
  double drawn = 0;
  total = 0;
  for (std::size_t e = 0; e < elements; ++e)
  {
    measures[e] = measure(e);
    total += measures[e];
    drawn += followGrading ? (measures[e] > 0 ? 1.0 : 0.0) : measures[e];
    cumulative[e] = drawn;
  }
  if (!(total > 0))
  {
    return;
  }
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  out.reserve(count);
  spacing.reserve(count);
  double weights = 0;
  for (int i = 0; i < count; ++i)
  {
    const double t = uniform(random) * drawn;
    const std::size_t e = std::min<std::size_t>(elements - 1, std::upper_bound(cumulative.begin(), cumulative.end(), t) - cumulative.begin());
    out.push_back(draw(e, uniform));
    spacing.push_back(followGrading ? std::pow(measures[e], 1.0 / dimension) : 1.0);
    if (share)
    {
      share->push_back(followGrading ? measures[e] : 1.0);
      weights += share->back();
    }
  }
  if (share)
  {
    for (double& w : *share)
    {
      w *= total / weights;
    }
  }
}

DenseSamples denseSampling(const SamplingDomain& domain, int surfaceCount, int volumeCount, const SamplingParameters& parameters,
  std::mt19937_64& random)
{
  DenseSamples dense;
  const PointList& x = domain.points;
  const bool grading = parameters.followMeshGrading;
  double area = 0;
  sampleElements(
    domain.triangles.size(), surfaceCount, 2, grading,
    [&](std::size_t t) {
      const auto& f = domain.triangles[t];
      return triangleArea(x[f[0]], x[f[1]], x[f[2]]);
    },
    [&](std::size_t t, std::uniform_real_distribution<double>& uniform) {
      const auto& f = domain.triangles[t];
      const double r1 = std::sqrt(uniform(random)), r2 = uniform(random); // uniform in a triangle
      return Vec3((1 - r1) * x[f[0]] + r1 * (1 - r2) * x[f[1]] + r1 * r2 * x[f[2]]);
    },
    random, dense.surface, dense.surfaceSpacing, nullptr, area);
  if (dense.surface.empty())
  {
    dense.surface = x; // a point cloud (or only degenerate faces): the points are the surface
    dense.surfaceSpacing.assign(x.size(), 1.0);
  }
  sampleElements(
    domain.tetrahedra.size(), volumeCount, 3, grading,
    [&](std::size_t t) {
      const auto& c = domain.tetrahedra[t];
      return tetrahedronVolume(x[c[0]], x[c[1]], x[c[2]], x[c[3]]);
    },
    [&](std::size_t t, std::uniform_real_distribution<double>& uniform) {
      const auto& c = domain.tetrahedra[t];
      // uniform in a tetrahedron: fold the unit cube (Rocchini & Cignoni 2000)
      double s = uniform(random), u = uniform(random), v = uniform(random);
      if (s + u > 1)
      {
        s = 1 - s;
        u = 1 - u;
      }
      if (u + v > 1)
      {
        const double tmp = v;
        v = 1 - s - u;
        u = 1 - tmp;
      }
      else if (s + u + v > 1)
      {
        const double tmp = v;
        v = s + u + v - 1;
        s = 1 - u - tmp;
      }
      return Vec3((1 - s - u - v) * x[c[0]] + s * x[c[1]] + u * x[c[2]] + v * x[c[3]]);
    },
    random, dense.volume, dense.volumeSpacing, &dense.volumeShare, dense.volumeOfDomain);
  if (dense.volume.empty() && volumeCount > 0)
  {
    // No volume cells: sample the padded bounding box around the input (no grading to follow).
    BoundingBox box = boundingBox(x);
    const double pad = parameters.boundsPadding * box.size().norm();
    box.lower.array() -= pad;
    box.upper.array() += pad;
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    dense.volume.reserve(volumeCount);
    for (int i = 0; i < volumeCount; ++i)
    {
      const Vec3 t(uniform(random), uniform(random), uniform(random));
      dense.volume.push_back(box.lower + t.cwiseProduct(box.size()));
    }
    dense.volumeOfDomain = box.size().prod();
    dense.volumeSpacing.assign(volumeCount, 1.0);
    dense.volumeShare.assign(volumeCount, dense.volumeOfDomain / volumeCount);
  }
  return dense;
}

PointList select(const PointList& points, const std::vector<int>& indices)
{
  PointList out;
  out.reserve(indices.size());
  for (int i : indices)
  {
    out.push_back(points[i]);
  }
  return out;
}

// Surface samples by farthest points on the surface, then volume samples by farthest points in
// the volume away from them, then a combined Lloyd relaxation with the surface weighted higher.
PointList placeSites(const DenseSamples& dense, int surfaceCount, int volumeCount, const SamplingParameters& parameters,
  const PointList& allDense, const std::vector<double>& weights, std::uint64_t seed, int& surfaceSites)
{
  PointList sites = select(dense.surface, farthestPointSelection(dense.surface, surfaceCount, {}, seed, dense.surfaceSpacing));
  surfaceSites = static_cast<int>(sites.size());
  const PointList volumeSites = select(dense.volume, farthestPointSelection(dense.volume, volumeCount, sites, seed + 1, dense.volumeSpacing));
  sites.insert(sites.end(), volumeSites.begin(), volumeSites.end());
  lloydRelaxation(sites, allDense, weights, parameters.lloydIterations);
  return sites;
}
} // namespace

BoundingBox boundingBox(const PointList& points)
{
  BoundingBox box;
  if (points.empty())
  {
    return box;
  }
  box.lower = box.upper = points.front();
  for (const Vec3& p : points)
  {
    box.lower = box.lower.cwiseMin(p);
    box.upper = box.upper.cwiseMax(p);
  }
  return box;
}

void requireFinite(const PointList& points, const char* what)
{
  for (const Vec3& p : points)
  {
    if (!p.allFinite())
    {
      throw InvalidInputException(std::string(what) + " contain NaN or infinite coordinates");
    }
  }
}

std::vector<int> farthestPointSelection(const PointList& candidates, int count, const PointList& alreadyChosen, std::uint64_t seed,
  const std::vector<double>& spacing)
{
  std::vector<int> chosen;
  if (candidates.empty() || count <= 0)
  {
    return chosen;
  }
  // A candidate's priority is its distance to the chosen points in units of its spacing.
  const auto unit = [&](std::size_t i) { return spacing.empty() ? 1.0 : spacing[i]; };
  // The tree's ball around candidate j holds the positions closer to it than its distance to the
  // chosen points as last stored (an upper bound of the current one): only a new point inside
  // that ball can bring j closer. Stored again whenever the number chosen doubles.
  KdTree candidateTree(candidates);
  std::vector<double> minDistance(candidates.size(), std::numeric_limits<double>::infinity());
  std::priority_queue<std::pair<double, int>> heap; // lazily refreshed: a stored priority bounds the current one
  if (alreadyChosen.empty())
  {
    std::mt19937_64 random(seed);
    heap.emplace(std::numeric_limits<double>::infinity(), static_cast<int>(random() % candidates.size()));
  }
  else
  {
    const KdTree chosenTree(alreadyChosen);
    for (std::size_t i = 0; i < candidates.size(); ++i)
    {
      minDistance[i] = (alreadyChosen[chosenTree.nearest(candidates[i])] - candidates[i]).norm();
      heap.emplace(minDistance[i] / unit(i), static_cast<int>(i));
    }
    candidateTree.setRadii(minDistance);
  }
  std::vector<int> nearby;
  std::size_t storeAt = 1;
  while (static_cast<int>(chosen.size()) < count && !heap.empty())
  {
    const auto [stored, i] = heap.top();
    heap.pop();
    const double priority = minDistance[i] / unit(i);
    if (stored > priority && !chosen.empty())
    {
      heap.emplace(priority, i);
      continue;
    }
    if (!(minDistance[i] > 0))
    {
      break; // only duplicates of chosen points are left
    }
    const bool first = chosen.empty() && alreadyChosen.empty();
    chosen.push_back(i);
    if (first)
    {
      nearby.resize(candidates.size());
      std::iota(nearby.begin(), nearby.end(), 0);
    }
    else
    {
      candidateTree.containing(candidates[i], nearby);
    }
    for (int j : nearby)
    {
      const double d = (candidates[j] - candidates[i]).norm();
      if (d < minDistance[j])
      {
        minDistance[j] = d;
        if (first)
        {
          heap.emplace(d / unit(j), j); // fill the heap
        }
      }
    }
    if (chosen.size() == storeAt)
    {
      candidateTree.setRadii(minDistance);
      storeAt *= 2;
    }
  }
  return chosen;
}

void lloydRelaxation(PointList& sites, const PointList& dense, const std::vector<double>& denseWeight, int iterations)
{
  std::vector<int> owner(dense.size());
  for (int iteration = 0; iteration < iterations && !sites.empty(); ++iteration)
  {
    const KdTree tree(sites);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < static_cast<long>(dense.size()); ++i)
    {
      owner[i] = tree.nearest(dense[i]);
    }
    PointList sum(sites.size(), Vec3::Zero());
    std::vector<double> weight(sites.size(), 0.0);
    for (std::size_t i = 0; i < dense.size(); ++i)
    {
      sum[owner[i]] += denseWeight[i] * dense[i];
      weight[owner[i]] += denseWeight[i];
    }
    for (std::size_t j = 0; j < sites.size(); ++j)
    {
      if (weight[j] > 0)
      {
        sites[j] = sum[j] / weight[j];
      }
    }
  }
}

std::vector<double> coverSupportRadii(const PointList& centers, const std::vector<const PointList*>& positions, double cover, bool volumeMesh)
{
  // The reach r_j of a sample starts at the distance to its s-th nearest fellow sample, so that
  // supports follow the local sample density (dense on the surface, coarse in the volume).
  const KdTree tree(centers);
  const int s = std::max(1, static_cast<int>(std::ceil(cover)));
  const long k = static_cast<long>(centers.size());
  std::vector<double> reach(centers.size(), 0.0);
#pragma omp parallel
  {
    std::vector<int> indices;
    std::vector<double> d2;
#pragma omp for schedule(static)
    for (long j = 0; j < k; ++j)
    {
      tree.kNearest(centers[j], s + 1, indices, d2); // the first is c_j itself
      reach[j] = std::sqrt(d2.back());
    }
  }
  // Then every position reached by fewer than s samples extends the reach of s samples: its s
  // nearest, or, on a graded volume mesh, the s that must grow least relative to their reach
  // (distance / reach). Beside a fine region (a body's dense surface samples) a position of a
  // coarse one is then covered by its coarse neighbours grown a little, not by fine samples grown
  // to the coarse scale, whose supports would reach thousands of the fine region's points (the
  // 64k-point hull case: 180 instead of 39 entries per row of Phi). Graded: reaches differ by more
  // than GradedSpread between the 10th and the 90th percentile. Elsewhere the nearest grow, which
  // keeps supports alike and overlapping: relative growth measured worse there (a uniform bar's
  // feature line residual 0.11 instead of 0.07 of its unconstrained violation; a surface, whose
  // spread comes from the padded box's coarse samples, had its points covered by those: a plane's
  // planarity residual 2x, its handle misfit 4x with the vertex energies of eq. 11).
  bool relative = false;
  if (volumeMesh && !reach.empty())
  {
    std::vector<double> sorted = reach;
    std::sort(sorted.begin(), sorted.end());
    relative = sorted[sorted.size() * 9 / 10] > GradedSpread * sorted[sorted.size() / 10];
  }
  KdTree reachTree(centers);
  reachTree.setRadii(reach);
  std::vector<double> extended = reach;
  for (const PointList* list : positions)
  {
    const long count = static_cast<long>(list->size());
    constexpr long Chunk = 4096;
    constexpr std::size_t Group = 16; // nearby positions sharing one search (the result does not depend on it)
#pragma omp parallel
    {
      std::vector<double> local(centers.size(), 0.0);
      std::vector<int> candidates, uncovered, indices;
      std::vector<double> squared;
#pragma omp for schedule(dynamic, 1) // the positions left uncovered cluster (a coarse region's)
      for (long first = 0; first < count; first += Chunk)
      {
        forEachNearbyGroup(*list, first, std::min(count, first + Chunk), Group,
          [&](const int* begin, const int* end, const Vec3& lower, const Vec3& upper) {
            // the positions of the group in fewer than s balls
            reachTree.meetingBox(lower, upper, candidates);
            uncovered.clear();
            for (const int* i = begin; i < end; ++i)
            {
              if (!reachTree.containedInAtLeast((*list)[*i], s, candidates))
              {
                uncovered.push_back(*i);
              }
            }
            if (uncovered.empty())
            {
              return;
            }
            if (relative)
            {
              Vec3 low = (*list)[uncovered[0]], high = low;
              for (int i : uncovered)
              {
                low = low.cwiseMin((*list)[i]);
                high = high.cwiseMax((*list)[i]);
              }
              reachTree.leastRelativeCandidates(low, high, s, candidates);
            }
            for (int i : uncovered)
            {
              const Vec3& x = (*list)[i];
              if (relative)
              {
                reachTree.kLeastRelative(x, s, candidates, indices, squared);
                for (std::size_t a = 0; a < indices.size(); ++a)
                {
                  squared[a] *= reach[indices[a]] * reach[indices[a]]; // the squared distance
                }
              }
              else
              {
                tree.kNearest(x, s, indices, squared);
              }
              for (std::size_t a = 0; a < indices.size(); ++a)
              {
                local[indices[a]] = std::max(local[indices[a]], std::sqrt(squared[a]) * (1 + 1e-9));
              }
            }
          });
      }
#pragma omp critical
      for (std::size_t j = 0; j < centers.size(); ++j)
      {
        extended[j] = std::max(extended[j], local[j]);
      }
    }
  }
  const double largest = *std::max_element(extended.begin(), extended.end());
  for (double& r : extended)
  {
    r = SupportMargin * (r > 0 ? r : largest);
  }
  return extended;
}

Samples sampleDomain(const SamplingDomain& domain, const SamplingParameters& parameters, const Progress& progress)
{
  if (domain.points.empty())
  {
    throw InvalidInputException("the input has no points");
  }
  requireFinite(domain.points, "input points");
  if (!(boundingBox(domain.points).size().norm() > 0))
  {
    throw InvalidInputException("all input points coincide: the domain has zero extent");
  }
  const int ks = std::max(0, parameters.numberOfSurfaceSamples);
  const int kv = std::max(0, parameters.numberOfVolumeSamples);
  if (ks + kv < 4)
  {
    throw InvalidInputException("at least 4 MLS samples are needed for a linear basis");
  }
  const double ratio = std::max(1.0, parameters.integrationPointRatio);
  const int ns = static_cast<int>(std::lround(ratio * ks)), nv = static_cast<int>(std::lround(ratio * kv));
  const int perSample = std::max(1, parameters.denseSamplesPerSample);

  std::mt19937_64 random(parameters.randomSeed);
  // Volume dense samples are always drawn: they measure the Voronoi volumes of integration points.
  DenseSamples dense = denseSampling(domain, perSample * (ks + ns), perSample * (kv + nv + ns), parameters, random);
  progress.report(0.1);

  PointList all = dense.surface;
  all.insert(all.end(), dense.volume.begin(), dense.volume.end());
  std::vector<double> weights(all.size(), 1.0);
  std::fill(weights.begin(), weights.begin() + dense.surface.size(), parameters.surfaceWeight);

  Samples out;
  out.centers = placeSites(dense, ks, kv, parameters, all, weights, parameters.randomSeed + 11, out.numberOfSurfaceCenters);
  progress.report(0.4);
  int surfaceIntegrationPoints = 0;
  out.integrationPoints = placeSites(dense, ns, nv, parameters, all, weights, parameters.randomSeed + 23, surfaceIntegrationPoints);
  progress.report(0.7);
  if (out.centers.size() < 4)
  {
    throw InvalidInputException("fewer than 4 distinct positions to place MLS samples at");
  }

  // V_i: the share of the volume's dense samples closest to q_i (Monte Carlo Voronoi volume).
  out.domainVolume = dense.volumeOfDomain;
  out.volume.assign(out.integrationPoints.size(), 0.0);
  if (!dense.volume.empty())
  {
    const KdTree tree(out.integrationPoints);
    std::vector<int> nearest(dense.volume.size());
#pragma omp parallel for schedule(static)
    for (long i = 0; i < static_cast<long>(dense.volume.size()); ++i)
    {
      nearest[i] = tree.nearest(dense.volume[i]);
    }
    for (std::size_t i = 0; i < dense.volume.size(); ++i) // summed in order: the same for any thread count
    {
      out.volume[nearest[i]] += dense.volumeShare[i];
    }
  }
  progress.report(0.8);
  out.supportRadius = coverSupportRadii(out.centers, { &out.integrationPoints, &domain.points }, parameters.cover,
    !domain.tetrahedra.empty());
  progress.report(1.0);
  return out;
}
} // namespace mlsdeform
