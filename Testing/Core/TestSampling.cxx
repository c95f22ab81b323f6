// Fig. 2 / section 5: farthest points, Lloyd relaxation, cover radii, Voronoi volumes.
#include "Common/HeapPages.h"
#include "Common/KdTree.h"
#include "Common/PositionIndex.h"
#include "Common/KeySort.h"
#include "Basis/MLSBasis.h"
#include "Sampling/Sampling.h"
#include "TestGeometry.h"
#include "../TestHarness.h"

#include <algorithm>
#include <numeric>
#include <random>

using namespace mlsdeform;
using testgeometry::randomPoints;

namespace
{
double minimumSpacing(const PointList& points)
{
  const KdTree tree(points);
  std::vector<int> indices;
  std::vector<double> d2;
  double spacing = std::numeric_limits<double>::infinity();
  for (const Vec3& p : points)
  {
    tree.kNearest(p, 2, indices, d2);
    spacing = std::min(spacing, std::sqrt(d2[1]));
  }
  return spacing;
}

SamplingParameters smallParameters()
{
  SamplingParameters p;
  p.numberOfSurfaceSamples = 150;
  p.numberOfVolumeSamples = 50;
  p.lloydIterations = 5;
  p.randomSeed = 7;
  return p;
}
}

TEST(KdTreeQueriesMatchBruteForce)
{
  const PointList points = randomPoints(2000, Vec3(0, 0, 0), Vec3(1, 1, 1), 1);
  std::vector<double> radii(points.size());
  for (std::size_t i = 0; i < radii.size(); ++i)
    radii[i] = 0.02 + 0.1 * (i % 7) / 7.0;
  KdTree tree(points);
  tree.setRadii(radii);
  std::vector<int> knn, containing;
  std::vector<double> d2;
  const PointList positions = randomPoints(100, Vec3(-0.1, -0.1, -0.1), Vec3(1.1, 1.1, 1.1), 2);
  for (std::size_t p = 0; p < positions.size(); ++p)
  {
    const Vec3& x = positions[p];
    // the searches shared by the positions of a box holding x: a point (p = 0), then boxes up to
    // 0.3 wide, larger than most balls
    const Vec3 lower = x - 0.1 * (p % 4) * Vec3(1.0, 0.5, 0.2), upper = x + 0.1 * (p % 3) * Vec3(0.3, 1.0, 0.6);
    std::vector<int> relative, candidates, meeting;
    std::vector<double> ratio2;
    tree.kNearest(x, 5, knn, d2);
    CHECK(tree.nearest(x) == knn[0]);
    for (int hint : { knn[0], knn[4], static_cast<int>(p) }) // a search bounded from the start finds the same
      CHECK(tree.nearest(x, hint) == knn[0]);
    tree.leastRelativeCandidates(lower, upper, 5, candidates);
    CHECK(std::is_sorted(candidates.begin(), candidates.end()));
    tree.kLeastRelative(x, 5, candidates, relative, ratio2);
    tree.containing(x, containing);
    tree.meetingBox(lower, upper, meeting);
    CHECK(std::is_sorted(meeting.begin(), meeting.end()));
    std::vector<int> filtered;
    for (int i : meeting)
    {
      if ((points[i] - x).squaredNorm() < radii[i] * radii[i])
        filtered.push_back(i);
    }
    CHECK(filtered == containing);
    std::vector<std::pair<double, int>> all, ratios;
    std::size_t containingCount = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const double d = (points[i] - x).norm();
      all.emplace_back(d, static_cast<int>(i));
      ratios.emplace_back(d / radii[i], static_cast<int>(i));
      containingCount += d < radii[i];
    }
    std::sort(all.begin(), all.end());
    std::sort(ratios.begin(), ratios.end());
    for (int a = 0; a < 5; ++a)
    {
      CHECK(knn[a] == all[a].second);
      CHECK(relative[a] == ratios[a].second);
      CHECK_NEAR(std::sqrt(ratio2[a]), ratios[a].first, 1e-12 * ratios[a].first); // a few roundings of ratios ~1
    }
    CHECK(containing.size() == containingCount);
    for (std::size_t count : { containingCount, containingCount + 1 })
      CHECK(tree.containedInAtLeast(x, static_cast<int>(count), meeting) == (containingCount >= count));
  }
}

TEST(PositionIndexNumbersDistinctPositions)
{
  // each distinct position (by its exact coordinates, -0 as +0) is numbered at its first
  // appearance; a position one ulp away is another; so many that the table probes past collisions
  PointList positions = randomPoints(5000, Vec3(0, 0, 0), Vec3(1, 1, 1), 7);
  positions.push_back(positions[10]);
  positions.push_back(Vec3(0, 0.5, 0.5));
  positions.push_back(Vec3(-0.0, 0.5, 0.5));
  positions.push_back(Vec3(std::nextafter(0.0, 1.0), 0.5, 0.5));
  const PositionIndex index(positions);
  CHECK(index.distinct().size() == 5002);
  CHECK(index.numbers()[5000] == 10 && index.numbers()[5001] == 5000 && index.numbers()[5002] == 5000 && index.numbers()[5003] == 5001);
  bool numbered = true;
  for (long i = 0; i < 5000; ++i)
    numbered = numbered && index.numbers()[i] == i && index.find(positions[i]) == i && index.distinct()[i] == positions[i];
  CHECK(numbered);
  CHECK(index.find(Vec3(-0.0, 0.5, 0.5)) == 5000 && index.find(Vec3(0.5, 0.5, 2)) == -1);
  CHECK(PositionIndex({}).find(Vec3::Zero()) == -1);
}

TEST(PopulatedHeapKeepsWhatItHolds)
{
  // blocks below glibc's mmap threshold live in the heap; faulting it in must not change them
  std::vector<std::vector<int>> blocks;
  for (int b = 0; b < 64; ++b)
  {
    blocks.emplace_back(1000 + 37 * b);
    std::iota(blocks.back().begin(), blocks.back().end(), 7 * b);
  }
  for (int b = 0; b < 64; b += 3)
  {
    blocks[b] = std::vector<int>(); // freed chunks in between
  }
  const std::size_t half = populateHeap(0.5);
  const std::size_t size = populateHeap();
#if defined(__linux__) && !defined(__SANITIZE_ADDRESS__) // AddressSanitizer's malloc does not use the heap
  CHECK(size > 0); // Linux 5.14+ (Debian 12: 6.1) populates
  CHECK(half % 4096 == 0 && half <= size / 2 && half + 4096 > size / 2); // whole pages, the lower half
#endif
  CHECK(populateHeap(0.0) == 0);
  for (int b = 0; b < 64; ++b)
  {
    for (std::size_t i = 0; i < blocks[b].size(); ++i)
    {
      CHECK(blocks[b][i] == 7 * b + static_cast<int>(i));
    }
  }
  std::vector<int> fresh(5000, 3); // and the heap still allocates
  CHECK(fresh[4999] == 3);
}

TEST(SortByKeyIsAStableSort)
{
  // keys of 0, 5, 11 (one pass), 30 and 63 bits (several passes), many ties among the short ones
  std::mt19937_64 random(3);
  for (int bits : { 0, 5, 11, 30, 63 })
  {
    std::vector<std::pair<std::uint64_t, long>> items(5000);
    for (std::size_t a = 0; a < items.size(); ++a)
    {
      items[a] = { bits == 0 ? 0 : random() >> (64 - bits), static_cast<long>(a) };
    }
    std::vector<std::pair<std::uint64_t, long>> expected = items;
    std::stable_sort(expected.begin(), expected.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    sortByKey(items, bits);
    CHECK(items == expected);
  }
  CHECK(keyBits(0) == 0);
  CHECK(keyBits(1) == 0);
  CHECK(keyBits(2) == 1);
  CHECK(keyBits(1024) == 10);
  CHECK(keyBits(1025) == 11);
}

TEST(FarthestPointSelectionSpreadsAndSkipsDuplicates)
{
  const PointList dense = randomPoints(5000, Vec3(0, 0, 0), Vec3(1, 1, 1), 3);
  const std::vector<int> chosen = farthestPointSelection(dense, 100, {}, 1);
  CHECK(chosen.size() == 100);
  PointList selected;
  for (int i : chosen)
    selected.push_back(dense[i]);
  const PointList random(dense.begin(), dense.begin() + 100);
  std::printf("spacing: farthest points %g, random points %g\n", minimumSpacing(selected), minimumSpacing(random));
  // Farthest points are spaced like a covering: 100 balls covering the unit cube need a radius
  // >= (3 / (400 pi))^(1/3) = 0.134, while the closest pair of 100 uniform points is expected
  // Gamma(4/3) (4/3 pi C(100, 2))^(-1/3) = 0.032 apart: a factor 4 in expectation, 3 required.
  CHECK(minimumSpacing(selected) > 3 * minimumSpacing(random));
  // Only three distinct positions: no more than three can be chosen.
  PointList duplicates;
  for (int i = 0; i < 30; ++i)
    duplicates.push_back(Vec3(i % 3, 0, 0));
  CHECK(farthestPointSelection(duplicates, 10, {}, 1).size() == 3);
}

TEST(LloydRelaxationMovesSitesToCentroids)
{
  // Two clusters and two sites placed badly: each site ends at its cluster's centroid.
  PointList dense = randomPoints(500, Vec3(0, 0, 0), Vec3(1, 1, 1), 4);
  const PointList second = randomPoints(500, Vec3(5, 0, 0), Vec3(6, 1, 1), 5);
  dense.insert(dense.end(), second.begin(), second.end());
  PointList sites = { Vec3(0, 0, 0), Vec3(6, 1, 1) };
  lloydRelaxation(sites, dense, std::vector<double>(dense.size(), 1.0), 3);
  Vec3 c0 = Vec3::Zero(), c1 = Vec3::Zero();
  for (int i = 0; i < 500; ++i)
  {
    c0 += dense[i] / 500;
    c1 += dense[500 + i] / 500;
  }
  // Exact after the first step (the clusters are 4 apart); both means sum 500 terms of size <= 6:
  // 500 eps 6 = 6.7e-13 per coordinate each, 2.3e-12 for the norm of their difference.
  CHECK((sites[0] - c0).norm() < 3e-12);
  CHECK((sites[1] - c1).norm() < 3e-12);
}

TEST(VolumeSamplingCoversTheDomain)
{
  const SamplingDomain box = testgeometry::tetrahedralBox(4, Vec3(2, 1, 1));
  const Samples samples = sampleDomain(box, smallParameters());
  CHECK(samples.centers.size() == 200);
  CHECK(samples.numberOfSurfaceCenters == 150);
  CHECK(samples.integrationPoints.size() == 800);
  CHECK_NEAR(samples.domainVolume, 2.0, 1e-12); // 384 tetrahedra of volume 1/192 summed: 384 eps 2 = 1.7e-13
  double total = 0;
  for (double v : samples.volume)
    total += v;
  // the 10 x (50 + 200 + 600) = 8500 volume dense samples add 2 / 8500 each: 8500 eps 2 = 3.8e-12
  CHECK_NEAR(total, 2.0, 1e-11);
  // every sampled position lies in at least s = 5 supports (the cover parameter, section 5)
  const MLSBasis basis(samples.centers, samples.supportRadius);
  ShapeFunctionValues phi;
  std::size_t fewest = 1000;
  for (const PointList* list : { &box.points, &samples.integrationPoints })
    for (const Vec3& x : *list)
    {
      basis.evaluate(x, phi, false);
      fewest = std::min(fewest, phi.index.size());
    }
  std::printf("fewest supports covering a position: %zu\n", fewest);
  CHECK(fewest >= 5);
  // surface samples are closer to the boundary than volume samples on average
  auto boundaryDistance = [](const Vec3& p) { return std::min({ p.x(), 2 - p.x(), p.y(), 1 - p.y(), p.z(), 1 - p.z() }); };
  double surface = 0, volume = 0;
  for (int j = 0; j < 200; ++j)
    (j < 150 ? surface : volume) += boundaryDistance(samples.centers[j]) / (j < 150 ? 150 : 50);
  std::printf("mean distance to the boundary: surface samples %g, volume samples %g\n", surface, volume);
  // Surface samples start on the boundary (distance 0); a Lloyd step moves each to the centroid of
  // its Voronoi cell. The cell of a site on the boundary ends at the bisector with the volume site
  // above it, at half that site's distance D from the boundary, so the centroid (of dense samples
  // at depths 0 to D / 2, the surface ones weighted 10) is at most D / 2 deep: over the sites,
  // surface < 0.5 x volume (the mean centroid is shallower still, the bound is the cell's depth).
  CHECK(surface < 0.5 * volume);
}

TEST(SamplesFollowTheMeshGrading)
{
  // A unit cube of 8^3 cells beside one of 4^3: the left half holds 8/9 of the elements.
  SamplingDomain graded = testgeometry::tetrahedralBox(8, Vec3(1, 1, 1));
  const SamplingDomain coarse = testgeometry::tetrahedralBox(4, Vec3(1, 1, 1));
  const int offset = static_cast<int>(graded.points.size());
  for (const Vec3& x : coarse.points)
    graded.points.push_back(x + Vec3(1, 0, 0));
  for (auto t : coarse.triangles)
    graded.triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
  for (auto t : coarse.tetrahedra)
    graded.tetrahedra.push_back({ t[0] + offset, t[1] + offset, t[2] + offset, t[3] + offset });
  for (bool follow : { false, true })
  {
    SamplingParameters p = smallParameters();
    p.followMeshGrading = follow;
    const Samples samples = sampleDomain(graded, p);
    int left = 0, leftIntegration = 0;
    double total = 0, leftVolume = 0;
    for (const Vec3& c : samples.centers)
      left += c.x() < 1;
    for (std::size_t i = 0; i < samples.integrationPoints.size(); ++i)
    {
      total += samples.volume[i];
      leftIntegration += samples.integrationPoints[i].x() < 1;
      leftVolume += samples.integrationPoints[i].x() < 1 ? samples.volume[i] : 0;
    }
    const double fraction = double(left) / samples.centers.size(), integrationFraction = double(leftIntegration) / samples.integrationPoints.size();
    std::printf("follow grading %d: %.3f of the samples and %.3f of the integration points in the fine half, holding %.4f of the volume (of %.12g)\n",
      follow, fraction, integrationFraction, leftVolume / total, total);
    // V_i are volumes whatever the density: they add up to the domain's volume (2), up to the
    // rounding of 8500 shares of size ~1e-3, and the two halves' shares to about 1 each (Monte
    // Carlo with ~1000 dense samples per half at least: a few percent, plus the cells of
    // integration points that straddle x = 1)
    CHECK_NEAR(total, 2.0, 1e-11);
    CHECK_NEAR(leftVolume / total, 0.5, 0.1);
    // uniform: about half of the samples in either half; following the grading: nearer 8/9 (the
    // element share) than 1/2 in both sets
    const double split = 0.5 * (0.5 + 8.0 / 9.0);
    CHECK(follow ? fraction > split && integrationFraction > split : fraction < split && integrationFraction < split);
  }
}

TEST(CoverGrowsCoarseSupportsOnGradedVolumes)
{
  // A body's fine samples (spacing 0.04 in a cube of side 0.16) among coarse ones (spacing 1/7)
  // and positions everywhere in the unit cube, as on a snappyHexMesh domain: growing each
  // uncovered position's nearest samples stretches the fine ones to the coarse scale; growing
  // those that grow least relative to their reach leaves them near their own. Without the
  // volume mesh flag, or on uniform samples, the nearest grow as before.
  PointList centers;
  int fine = 0;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 4; ++j)
      for (int k = 0; k <= 4; ++k, ++fine)
        centers.push_back(Vec3(0.42, 0.42, 0.42) + 0.04 * Vec3(i, j, k));
  const double coarse = 1.0 / 7;
  for (int i = 0; i <= 7; ++i)
    for (int j = 0; j <= 7; ++j)
      for (int k = 0; k <= 7; ++k)
        centers.push_back(coarse * Vec3(i, j, k));
  const PointList positions = randomPoints(4000, Vec3(0, 0, 0), Vec3(1, 1, 1), 3);
  double entries[2] = { 0, 0 }, largestFine[2] = { 0, 0 };
  for (bool volumeMesh : { false, true })
  {
    const std::vector<double> radii = coverSupportRadii(centers, { &positions }, 5, volumeMesh);
    KdTree tree(centers);
    std::vector<double> reach(radii.size());
    for (std::size_t j = 0; j < radii.size(); ++j)
      reach[j] = radii[j] / 1.5; // the cover holds at the reach, 1 / SupportMargin of the radius
    tree.setRadii(reach);
    std::size_t fewest = 1000;
    std::vector<int> covering;
    for (const Vec3& x : positions)
    {
      tree.containing(x, covering);
      fewest = std::min(fewest, covering.size());
    }
    tree.setRadii(radii);
    for (const Vec3& x : positions)
    {
      tree.containing(x, covering);
      entries[volumeMesh] += double(covering.size()) / positions.size();
    }
    for (int j = 0; j < fine; ++j)
      largestFine[volumeMesh] = std::max(largestFine[volumeMesh], radii[j]);
    std::printf("volume mesh %d: fewest supports covering a position %zu, mean %.1f, largest fine radius %.3f\n", volumeMesh, fewest,
      entries[volumeMesh], largestFine[volumeMesh]);
    CHECK(fewest >= 5);
  }
  // Relative growth keeps every fine support below the coarse spacing, which a fine sample
  // covering a coarse position beside the body must exceed, and so fewer supports per position.
  CHECK(largestFine[1] < coarse && largestFine[0] > coarse);
  CHECK(entries[1] < entries[0]);
  // uniform samples: the same radii either way
  const PointList uniform = randomPoints(500, Vec3(0, 0, 0), Vec3(1, 1, 1), 4);
  CHECK(coverSupportRadii(uniform, { &positions }, 5, true) == coverSupportRadii(uniform, { &positions }, 5, false));
}

TEST(SurfaceOnlyInputSamplesPaddedBox)
{
  const SamplingDomain plane = testgeometry::triangulatedPlane(10, 10, 1, 1);
  const Samples samples = sampleDomain(plane, smallParameters());
  const double pad = 0.1 * std::sqrt(2.0);
  // a product of three side lengths <= 1.3, each a few roundings: ~10 eps 1.3 = 3e-15
  CHECK_NEAR(samples.domainVolume, (1 + 2 * pad) * (1 + 2 * pad) * 2 * pad, 1e-14);
  double maxHeight = 0;
  for (const Vec3& c : samples.centers)
    maxHeight = std::max(maxHeight, std::abs(c.z()));
  std::printf("largest height %g of the padding %g\n", maxHeight, pad);
  // volume samples fill the space around the plane: fewer than all 50 lie in the middle 30% of the
  // slab (uniform ones would with probability 0.3^50)
  CHECK(maxHeight > 0.3 * pad);
  // and stay in the padded box: Lloyd centroids are means of up to 8500 dense samples with
  // |z| <= pad, which round to at most 8500 eps pad = 2.6e-13 beyond it
  CHECK(maxHeight <= pad + 1e-12);
}

TEST(SameSeedSameSamples)
{
  const SamplingDomain box = testgeometry::tetrahedralBox(3, Vec3(1, 1, 1));
  SamplingParameters p = smallParameters();
  const Samples a = sampleDomain(box, p), b = sampleDomain(box, p);
  p.randomSeed = 8;
  const Samples c = sampleDomain(box, p);
  bool same = a.centers.size() == b.centers.size(), different = false;
  for (std::size_t j = 0; same && j < a.centers.size(); ++j)
  {
    same = a.centers[j] == b.centers[j] && a.supportRadius[j] == b.supportRadius[j];
    different = different || a.centers[j] != c.centers[j];
  }
  CHECK(same);
  CHECK(different);
}

TEST(BadDomainsAreRejected)
{
  SamplingDomain empty;
  CHECK_THROWS(sampleDomain(empty, smallParameters()), InvalidInputException);
  SamplingDomain nan = testgeometry::triangulatedPlane(2, 2, 1, 1);
  nan.points[3].y() = std::nan("");
  CHECK_THROWS(sampleDomain(nan, smallParameters()), InvalidInputException);
  SamplingDomain coincident;
  coincident.points.assign(10, Vec3(1, 2, 3));
  CHECK_THROWS(sampleDomain(coincident, smallParameters()), InvalidInputException);
}

TEST_MAIN
