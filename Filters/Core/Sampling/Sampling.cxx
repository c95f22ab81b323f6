#include "Sampling/Sampling.h"

#include "Common/KdTree.h"
#include "Common/PositionHash.h"
#include "Common/ZOrder.h"

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
// the farthest-point selection) and, in the volume, its share of the domain's volume. Sorted by
// their coordinates: the same list however the elements were ordered or split over processes.
struct DenseSamples
{
  PointList surface;
  std::vector<double> surfaceSpacing;
  PointList volume;
  std::vector<double> volumeSpacing;
  std::vector<double> volumeShare; // sums to volumeOfDomain
  double volumeOfDomain = 0;
};

// A dense sample as gathered: x, y, z, spacing, share.
constexpr std::size_t DenseFields = 5;

double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c)
{
  return 0.5 * (b - a).cross(c - a).norm();
}

double tetrahedronVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return std::abs((b - a).dot((c - a).cross(d - a))) / 6.0;
}

// An element's vertex positions in lexicographic order: what is computed from them (measure,
// samples) does not depend on the order in which the element was stored.
template <std::size_t N>
std::array<Vec3, N> sortedVertices(const PointList& x, const std::array<int, N>& element)
{
  std::array<Vec3, N> v;
  for (std::size_t k = 0; k < N; ++k)
  {
    v[k] = x[element[k]];
  }
  std::sort(v.begin(), v.end(), [](const Vec3& a, const Vec3& b) { return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3); });
  return v;
}

template <std::size_t N>
double simplexMeasure(const std::array<Vec3, N>& v)
{
  if constexpr (N == 3)
  {
    return triangleArea(v[0], v[1], v[2]);
  }
  else
  {
    return tetrahedronVolume(v[0], v[1], v[2], v[3]);
  }
}

// A uniform point in a triangle or (folding the unit cube, Rocchini & Cignoni 2000) a tetrahedron.
template <std::size_t N>
Vec3 uniformPoint(const std::array<Vec3, N>& v, KeyedRandom& random)
{
  if constexpr (N == 3)
  {
    const double r1 = std::sqrt(random.uniform()), r2 = random.uniform();
    return (1 - r1) * v[0] + r1 * (1 - r2) * v[1] + r1 * r2 * v[2];
  }
  else
  {
    double s = random.uniform(), u = random.uniform(), w = random.uniform();
    if (s + u > 1)
    {
      s = 1 - s;
      u = 1 - u;
    }
    if (u + w > 1)
    {
      const double tmp = w;
      w = 1 - s - u;
      u = 1 - tmp;
    }
    else if (s + u + w > 1)
    {
      const double tmp = w;
      w = s + u + w - 1;
      s = 1 - u - tmp;
    }
    return (1 - s - u - w) * v[0] + s * v[1] + u * v[2] + w * v[3];
  }
}

// The sum of the measures over all processes, exactly: each in fixed point (2^62 units of the
// largest), summed as integers in 32-bit limbs, so that it does not depend on the split or order.
double exactTotal(const UninitializedVector<double>& measures, const Collective& group)
{
  std::vector<double> largest{ 0.0 };
  for (double m : measures)
  {
    largest[0] = std::max(largest[0], m);
  }
  group.maximum(largest);
  if (!(largest[0] > 0))
  {
    return 0;
  }
  unsigned __int128 local = 0;
  for (double m : measures)
  {
    local += static_cast<std::uint64_t>(std::llround(std::ldexp(m / largest[0], 62)));
  }
  std::vector<std::int64_t> limbs(4);
  for (int l = 0; l < 4; ++l)
  {
    limbs[l] = static_cast<std::int64_t>((local >> (32 * l)) & 0xffffffffULL);
  }
  group.sum(limbs);
  unsigned __int128 total = 0;
  for (int l = 0; l < 4; ++l)
  {
    total += static_cast<unsigned __int128>(limbs[l]) << (32 * l);
  }
  return std::ldexp(static_cast<double>(total), -62) * largest[0];
}

// Dense samples of the triangles (N = 3) or tetrahedra (N = 4) of all processes, about `count`
// in all: each element of positive measure draws floor(lambda) or floor(lambda) + 1 points
// (expected lambda = count / elements following the grading, count * measure / total
// otherwise), uniform within it, from random numbers keyed by its vertices' positions (sorted, so
// that the element draws the same wherever it is stored). Each point gets the spacing
// measure^(1/dimension) of its element (1 when uniform) and the share measure (1 when uniform);
// out gets every process's points sorted, total the measure of all elements.
template <std::size_t N>
void sampleSimplices(const PointList& x, const UninitializedVector<std::uint64_t>& keys, const Simplices<N>& elements, int count,
  bool grading, std::uint64_t seed, const Collective& group, std::vector<double>& out, double& total)
{
  const long n = static_cast<long>(elements.size());
  UninitializedVector<double> measures(elements.size()); // set by the loop below
#pragma omp parallel for schedule(static)
  for (long e = 0; e < n; ++e)
  {
    measures[e] = simplexMeasure(sortedVertices(x, elements[e]));
  }
  total = exactTotal(measures, group);
  std::vector<std::int64_t> positive{ static_cast<std::int64_t>(std::count_if(measures.begin(), measures.end(), [](double m) { return m > 0; })) };
  group.sum(positive);
  std::vector<double> local;
  if (total > 0 && count > 0)
  {
    const std::uint64_t salt = mixBits(seed * 0x9e3779b97f4a7c15ULL + N);
#pragma omp parallel
    {
      std::vector<double> mine; // the order does not matter: the samples are sorted below
#pragma omp for schedule(static) nowait
      for (long e = 0; e < n; ++e)
      {
        if (!(measures[e] > 0))
        {
          continue;
        }
        std::uint64_t key = salt;
        for (std::size_t k = 0; k < N; ++k)
        {
          key += keys[elements[e][k]]; // a sum: the same for any vertex order
        }
        KeyedRandom random(key);
        const double lambda = grading ? count / static_cast<double>(positive[0]) : count * measures[e] / total;
        const double whole = std::floor(lambda);
        const int draws = static_cast<int>(whole) + (random.uniform() < lambda - whole ? 1 : 0);
        if (draws == 0)
        {
          continue;
        }
        const std::array<Vec3, N> v = sortedVertices(x, elements[e]);
        for (int d = 0; d < draws; ++d)
        {
          const Vec3 p = uniformPoint(v, random);
          mine.insert(mine.end(), { p[0], p[1], p[2], grading ? std::pow(measures[e], 1.0 / (N - 1)) : 1.0, grading ? measures[e] : 1.0 });
        }
      }
#pragma omp critical
      local.insert(local.end(), mine.begin(), mine.end());
    }
  }
  out = group.gather(local);
  // sorted as tuples of DenseFields values
  std::vector<std::size_t> order(out.size() / DenseFields);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(&out[a * DenseFields], &out[a * DenseFields] + DenseFields, &out[b * DenseFields], &out[b * DenseFields] + DenseFields);
  });
  std::vector<double> sorted(out.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    std::copy_n(&out[order[i] * DenseFields], DenseFields, &sorted[i * DenseFields]);
  }
  out = std::move(sorted);
}

// Splits gathered dense samples into positions, spacings and shares.
void unpack(const std::vector<double>& flat, PointList& points, std::vector<double>& spacing, std::vector<double>* share)
{
  for (std::size_t i = 0; i + DenseFields <= flat.size(); i += DenseFields)
  {
    points.emplace_back(flat[i], flat[i + 1], flat[i + 2]);
    spacing.push_back(flat[i + 3]);
    if (share)
    {
      share->push_back(flat[i + 4]);
    }
  }
}

DenseSamples denseSampling(const SamplingDomain& domain, int surfaceCount, int volumeCount, const SamplingParameters& parameters,
  const Collective& group)
{
  DenseSamples dense;
  const PointList& x = domain.points;
  const bool grading = parameters.followMeshGrading;
  // the vertices' keys (PositionHash.h), summed per element
  UninitializedVector<std::uint64_t> keys(x.size()); // set by the loop below
#pragma omp parallel for schedule(static)
  for (long i = 0; i < static_cast<long>(x.size()); ++i)
  {
    keys[i] = positionKey(x[i]);
  }
  std::vector<double> flat;
  double area = 0;
  sampleSimplices(x, keys, domain.triangles, surfaceCount, grading, parameters.randomSeed, group, flat, area);
  unpack(flat, dense.surface, dense.surfaceSpacing, nullptr);
  if (dense.surface.empty())
  {
    // a point cloud (or only degenerate faces): the points of all processes are the surface,
    // sorted, each position once
    std::vector<double> local;
    for (const Vec3& p : x)
    {
      local.insert(local.end(), { p[0], p[1], p[2] });
    }
    const std::vector<double> all = group.gather(local);
    for (std::size_t i = 0; i < all.size(); i += 3)
    {
      dense.surface.emplace_back(all[i], all[i + 1], all[i + 2]);
    }
    std::sort(dense.surface.begin(), dense.surface.end(), [](const Vec3& a, const Vec3& b) { return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3); });
    dense.surface.erase(std::unique(dense.surface.begin(), dense.surface.end()), dense.surface.end());
    dense.surfaceSpacing.assign(dense.surface.size(), 1.0);
  }
  sampleSimplices(x, keys, domain.tetrahedra, volumeCount, grading, parameters.randomSeed, group, flat, dense.volumeOfDomain);
  unpack(flat, dense.volume, dense.volumeSpacing, &dense.volumeShare);
  double shares = 0;
  for (double w : dense.volumeShare)
  {
    shares += w;
  }
  for (double& w : dense.volumeShare)
  {
    w *= dense.volumeOfDomain / shares; // a Monte Carlo estimate of the volume nearest to each point
  }
  if (dense.volume.empty() && volumeCount > 0)
  {
    // No volume cells: sample the padded bounding box around the input (no grading to follow).
    BoundingBox box = boundingBox(x, group);
    const double pad = parameters.boundsPadding * box.size().norm();
    box.lower.array() -= pad;
    box.upper.array() += pad;
    std::mt19937_64 random(parameters.randomSeed);
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
  const PointList& allDense, const std::vector<double>& weights, std::uint64_t seed, int& surfaceSites, const Progress& progress)
{
  PointList sites = select(dense.surface, farthestPointSelection(dense.surface, surfaceCount, {}, seed, dense.surfaceSpacing, progress));
  surfaceSites = static_cast<int>(sites.size());
  const PointList volumeSites =
    select(dense.volume, farthestPointSelection(dense.volume, volumeCount, sites, seed + 1, dense.volumeSpacing, progress));
  sites.insert(sites.end(), volumeSites.begin(), volumeSites.end());
  lloydRelaxation(sites, allDense, weights, parameters.lloydIterations, progress);
  return sites;
}
// A sample closer than this fraction of a kept sample's support radius to it is merged into it.
constexpr double MergeDistance = 0.1;

// Merges samples that lie within MergeDistance of the support radius of a sample kept before
// them (in order, surface samples first): their shape functions are nearly the same function,
// so the system of eq. 14 cannot tell their coefficients apart (a sampling finer than the mesh:
// the sphereChannel case's 19,697 points with k = 20,000 put samples at 2% of their radius from
// each other). The basis loses a nearly redundant function, not a part of the space it spans.
// Returns whether any was merged (the radii are then to be computed again).
bool mergeCloseSamples(PointList& centers, const std::vector<double>& radius, int& numberOfSurfaceCenters)
{
  std::vector<double> reach(radius.size());
  std::transform(radius.begin(), radius.end(), reach.begin(), [](double r) { return MergeDistance * r; });
  KdTree tree(centers);
  tree.setRadii(reach);
  std::vector<char> kept(centers.size(), 1);
  std::vector<int> near;
  for (std::size_t j = 0; j < centers.size(); ++j)
  {
    tree.containing(centers[j], near);
    kept[j] = std::none_of(near.begin(), near.end(), [&](int i) { return static_cast<std::size_t>(i) < j && kept[i]; });
  }
  if (std::all_of(kept.begin(), kept.end(), [](char k) { return k != 0; }))
  {
    return false;
  }
  PointList merged;
  int surface = 0;
  for (std::size_t j = 0; j < centers.size(); ++j)
  {
    if (kept[j])
    {
      merged.push_back(centers[j]);
      surface += static_cast<int>(j) < numberOfSurfaceCenters ? 1 : 0;
    }
  }
  centers = std::move(merged);
  numberOfSurfaceCenters = surface;
  return true;
}
} // namespace

std::vector<int> farthestPointSelection(const PointList& candidates, int count, const PointList& alreadyChosen, std::uint64_t seed,
  const std::vector<double>& spacing, const Progress& progress)
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
    const long n = static_cast<long>(candidates.size());
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i)
    {
      minDistance[i] = (alreadyChosen[chosenTree.nearest(candidates[i])] - candidates[i]).norm();
    }
    for (long i = 0; i < n; ++i)
    {
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
    if (chosen.size() % 256 == 0)
    {
      progress.stopIfAsked();
    }
  }
  return chosen;
}

void lloydRelaxation(PointList& sites, const PointList& dense, const std::vector<double>& denseWeight, int iterations, const Progress& progress)
{
  std::vector<int> owner(dense.size(), -1);
  for (int iteration = 0; iteration < iterations && !sites.empty(); ++iteration)
  {
    progress.stopIfAsked();
    const KdTree tree(sites);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < static_cast<long>(dense.size()); ++i)
    {
      owner[i] = tree.nearest(dense[i], owner[i]); // the sites moved little: the last owner bounds the search
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

std::vector<double> coverSupportRadii(const PointList& centers, const std::vector<const PointList*>& positions, double cover, bool volumeMesh,
  const PointList& measured, const Collective& group)
{
  // The reach r_j of a sample starts at the distance to its s-th nearest fellow sample, so that
  // supports follow the local sample density (dense on the surface, coarse in the volume), and
  // reaches at least s measured points: a sample whose support holds fewer is barely seen by
  // the energies (eq. 12, 13 sum over the integration points), and its coefficient is then
  // determined by little but round-off (the sphereChannel case with k = 4000: supports with a
  // single integration point of nonzero volume, a system of reciprocal condition below 1e-12).
  const KdTree tree(centers);
  const KdTree measuredTree(measured);
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
      if (static_cast<long>(measured.size()) >= s)
      {
        measuredTree.kNearest(centers[j], s, indices, d2);
        reach[j] = std::max(reach[j], std::sqrt(d2.back()) * (1 + 1e-9));
      }
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
    // nearby positions sharing one search (the result does not depend on it): on the 400k hull
    // case the sampling took 0.60-0.65 s with 16, 0.58-0.59 s with 32, 0.58-0.60 s with 64
    constexpr std::size_t Group = 32;
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
  group.maximum(extended); // each process covered its own positions
  const double largest = *std::max_element(extended.begin(), extended.end());
  for (double& r : extended)
  {
    r = SupportMargin * (r > 0 ? r : largest);
  }
  return extended;
}

Samples sampleDomain(const SamplingDomain& domain, const SamplingParameters& parameters, const Progress& progress, const Collective& group)
{
  agree(group, [&] { requireFinite(domain.points, "input points"); });
  if (!group.any(!domain.points.empty()))
  {
    throw InvalidInputException("the input has no points");
  }
  if (!(boundingBox(domain.points, group).size().norm() > 0))
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

  // Volume dense samples are always drawn: they measure the Voronoi volumes of integration points.
  DenseSamples dense = denseSampling(domain, perSample * (ks + ns), perSample * (kv + nv + ns), parameters, group);
  progress.report(0.1);

  PointList all = dense.surface;
  all.insert(all.end(), dense.volume.begin(), dense.volume.end());
  std::vector<double> weights(all.size(), 1.0);
  std::fill(weights.begin(), weights.begin() + dense.surface.size(), parameters.surfaceWeight);

  Samples out;
  out.centers = placeSites(dense, ks, kv, parameters, all, weights, parameters.randomSeed + 11, out.numberOfSurfaceCenters, progress);
  progress.report(0.4);
  int surfaceIntegrationPoints = 0;
  out.integrationPoints =
    placeSites(dense, ns, nv, parameters, all, weights, parameters.randomSeed + 23, surfaceIntegrationPoints, progress);
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
  PointList measured; // the integration points the energies see: those with a volume
  for (std::size_t i = 0; i < out.integrationPoints.size(); ++i)
  {
    if (out.volume[i] > 0)
    {
      measured.push_back(out.integrationPoints[i]);
    }
  }
  const bool volumeMesh = group.any(!domain.tetrahedra.empty());
  out.supportRadius = coverSupportRadii(out.centers, { &out.integrationPoints, &domain.points }, parameters.cover, volumeMesh, measured, group);
  if (mergeCloseSamples(out.centers, out.supportRadius, out.numberOfSurfaceCenters))
  {
    out.supportRadius = coverSupportRadii(out.centers, { &out.integrationPoints, &domain.points }, parameters.cover, volumeMesh, measured, group);
  }
  progress.report(1.0);
  return out;
}
} // namespace mlsdeform
