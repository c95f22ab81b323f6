// Section 6.3: primitives from minimal sets and least squares, the forward search, and the
// efficient RANSAC on generated CAD-like parts, clean and noisy.
#include "../TestHarness.h"
#include "Primitives/EfficientRansac.h"
#include "Primitives/FaceSamples.h"
#include "SyntheticParts.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <map>

using namespace mlsdeform;
using namespace syntheticparts;

namespace
{
double degrees(double radians)
{
  return radians * 180 / M_PI;
}

// Angle between two axes or normals, ignoring their sign (degrees).
double axisAngle(const Vec3& a, const Vec3& b)
{
  return degrees(std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))));
}

struct Detection
{
  FaceSamples samples;
  std::vector<DetectedPrimitive> found;
  RansacParameters parameters;
};

RansacParameters defaults(double diagonal)
{
  RansacParameters p;
  p.epsilon = 0.005 * diagonal;
  p.clusterEpsilon = 0.02 * diagonal;
  p.normalThreshold = 20 * M_PI / 180;
  p.minimumSupport = 30;
  p.probability = 0.95;
  return p;
}

Detection detect(const Part& part, std::uint64_t seed = 0)
{
  Detection d;
  d.samples = faceSamples(part.points, part.faces);
  d.parameters = defaults(part.diagonal());
  d.parameters.seed = seed;
  const SampleFaces faces{ part.faces, part.points };
  d.found = detectPrimitives(d.samples.barycenters, d.samples.normals, d.parameters, &faces);
  return d;
}

// The detected primitive of every face, -1 for none.
std::vector<int> assignedPrimitives(const Part& part, const std::vector<DetectedPrimitive>& found)
{
  std::vector<int> assigned(part.faces.size(), -1);
  for (std::size_t d = 0; d < found.size(); ++d)
    for (int f : found[d].members)
      assigned[f] = static_cast<int>(d);
  return assigned;
}

// Each generated primitive is matched to the detected primitive of its type that holds most of
// its faces (one to one, largest overlaps first); a face is right when its detected primitive is
// matched to its generated one. Returns the fraction of right faces and the matches.
double rightFraction(const Part& part, const std::vector<DetectedPrimitive>& found, std::map<int, int>& match)
{
  const std::vector<int> assigned = assignedPrimitives(part, found);
  std::map<std::pair<int, int>, int> overlap; // (truth, detected) -> faces
  for (std::size_t f = 0; f < part.faces.size(); ++f)
    if (assigned[f] >= 0 && found[assigned[f]].shape.type == part.primitives[part.truth[f]].type)
      ++overlap[{ part.truth[f], assigned[f] }];
  std::vector<std::pair<int, std::pair<int, int>>> byOverlap;
  for (const auto& [key, count] : overlap)
    byOverlap.push_back({ count, key });
  std::sort(byOverlap.rbegin(), byOverlap.rend());
  match.clear();
  std::map<int, int> taken;
  for (const auto& [count, key] : byOverlap)
    if (!match.count(key.first) && !taken.count(key.second))
    {
      match[key.first] = key.second;
      taken[key.second] = key.first;
    }
  long right = 0;
  for (std::size_t f = 0; f < part.faces.size(); ++f)
    right += match.count(part.truth[f]) && match[part.truth[f]] == assigned[f];
  return static_cast<double>(right) / part.faces.size();
}

// The mean radial offset of the face barycenters of a generated sphere or cylinder from its
// surface: a face's barycenter lies inside by about its squared size / (2 radius), 1.45% of
// the radius for the sphere of separatePrimitives(0.1), which no fit to the faces undoes.
double facetingOffset(const Part& part, const Detection& d, int truth)
{
  const Primitive& t = part.primitives[truth];
  double sum = 0;
  long count = 0;
  for (std::size_t f = 0; f < part.faces.size(); ++f)
    if (part.truth[f] == truth)
    {
      const Vec3 r = d.samples.barycenters[f] - t.center;
      sum += (t.type == PrimitiveType::Sphere ? r.norm() : (r - r.dot(t.axis) * t.axis).norm()) - t.radius;
      ++count;
    }
  return sum / static_cast<double>(count);
}

// The paper's quality targets on a part: >= 95% of the faces right, every generated primitive
// found with radii within 1% (plus the faceting offset of its face barycenters) and axes and
// normals within 1 degree.
void checkQuality(const Part& part, const Detection& d)
{
  std::map<int, int> match;
  const double right = rightFraction(part, d.found, match);
  std::printf("%zu faces, %zu primitives found, %.2f%% of the faces right\n", part.faces.size(), d.found.size(), 100 * right);
  CHECK(right >= 0.95);
  CHECK(match.size() == part.primitives.size());
  for (const auto& [truth, detected] : match)
  {
    const Primitive& t = part.primitives[truth];
    const Primitive& s = d.found[detected].shape;
    std::printf("  %-8s %5zu faces: axis %.3f deg, radius %.3f%%, angle %.3f deg, rms %.2e\n", primitiveTypeName(s.type),
      d.found[detected].members.size(), t.type == PrimitiveType::Sphere ? 0.0 : axisAngle(t.axis, s.axis),
      t.radius > 0 ? 100 * std::abs(s.radius / t.radius - 1) : 0.0, degrees(std::abs(s.angle - t.angle)), d.found[detected].rmsDistance);
    if (t.type != PrimitiveType::Sphere)
      CHECK(axisAngle(t.axis, s.axis) <= 1.0);
    if (t.type == PrimitiveType::Sphere || t.type == PrimitiveType::Cylinder)
      CHECK(std::abs(s.radius - t.radius) <= 0.01 * t.radius + std::abs(facetingOffset(part, d, truth)));
    if (t.type == PrimitiveType::Cone)
      CHECK(degrees(std::abs(s.angle - t.angle)) <= 1.0);
  }
}
}

TEST(DistancesAndNormalsOfThePrimitives)
{
  Primitive cylinder;
  cylinder.type = PrimitiveType::Cylinder;
  cylinder.axis = Vec3(0, 0, 1);
  cylinder.center = Vec3(1, 1, 0);
  cylinder.radius = 2;
  CHECK_NEAR(cylinder.distance(Vec3(1, 4, 7)), 1.0, 1e-15);
  CHECK((cylinder.normalAt(Vec3(1, 4, 7)) - Vec3(0, 1, 0)).norm() < 1e-15);
  Primitive sphere;
  sphere.type = PrimitiveType::Sphere;
  sphere.center = Vec3(0, 0, 1);
  sphere.radius = 1;
  CHECK_NEAR(sphere.distance(Vec3(0, 3, 1)), 2.0, 1e-15);
  // a 45 degree cone opening upwards from the origin: (1, 0, 1) is on it, (0, 0, 1) is
  // 1/sqrt(2) away, and below the apex the apex is closest
  Primitive cone;
  cone.type = PrimitiveType::Cone;
  cone.axis = Vec3(0, 0, 1);
  cone.setAngle(M_PI / 4);
  CHECK_NEAR(cone.distance(Vec3(1, 0, 1)), 0.0, 1e-15);
  CHECK_NEAR(cone.distance(Vec3(0, 0, 1)), std::sqrt(0.5), 1e-15);
  CHECK_NEAR(cone.distance(Vec3(0, 0, -2)), 2.0, 1e-15);
  CHECK((cone.normalAt(Vec3(2, 0, 2)) - Vec3(1, 0, -1).normalized()).norm() < 1e-15);
  const Primitive plane = syntheticparts::plane(Vec3(0, 0, 2), Vec3(5, 5, 3));
  CHECK_NEAR(plane.distance(Vec3(0, 0, 1)), 2.0, 1e-15);
}

TEST(MinimalSetsDetermineThePrimitives)
{
  // three oriented samples on each generated primitive give it back exactly
  const Part part = blockWithFeatures(0.1, 48);
  for (std::size_t label = 0; label < part.primitives.size(); ++label)
  {
    const Primitive& truth = part.primitives[label];
    std::vector<int> faces;
    for (std::size_t f = 0; f < part.faces.size(); ++f)
      if (part.truth[f] == static_cast<int>(label))
        faces.push_back(static_cast<int>(f));
    // vertices on the surface with the exact normals there (face barycenters are off by the
    // faceting); the second where the normal has turned by 30 to 150 degrees (if it does)
    const Vec3 first = part.points[part.faces[faces[0]][0]];
    Vec3 second = part.points[part.faces[faces[faces.size() / 2]][1]];
    for (int f : faces)
    {
      const double turn = axisAngle(truth.normalAt(part.points[part.faces[f][0]]), truth.normalAt(first));
      if (turn > 30 && turn < 150 && std::abs(truth.normalAt(part.points[part.faces[f][0]]).dot(truth.normalAt(first))) < 0.8)
      {
        second = part.points[part.faces[f][0]];
        break;
      }
    }
    const Vec3 p[3] = { first, second, part.points[part.faces[faces[2 * faces.size() / 3]][2]] };
    const Vec3 n[3] = { truth.normalAt(p[0]), truth.normalAt(p[1]), truth.normalAt(p[2]) };
    const std::optional<Primitive> fit = fitMinimal(truth.type, p, n, 1e-9, std::cos(1e-6));
    CHECK(fit.has_value());
    if (!fit)
      continue;
    CHECK(fit->type == truth.type);
    for (int f : faces)
      for (int v : part.faces[f])
        CHECK(fit->distance(part.points[v]) < 1e-9);
    CHECK(axisAngle(fit->axis, truth.axis) < 1e-6 || truth.type == PrimitiveType::Sphere);
    CHECK_NEAR(fit->radius, truth.radius, 1e-9);
    CHECK_NEAR(fit->angle, truth.angle, 1e-9);
  }
  // degenerate sets give nothing: collinear points, parallel normals for a cylinder
  const Vec3 line[3] = { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0) };
  const Vec3 up[3] = { Vec3::UnitZ(), Vec3::UnitZ(), Vec3::UnitZ() };
  CHECK(!fitMinimal(PrimitiveType::Plane, line, up, 0.1, 0.9));
  CHECK(!fitMinimal(PrimitiveType::Cylinder, line, up, 0.1, 0.9));
  CHECK(!fitMinimal(PrimitiveType::Sphere, line, up, 0.1, 0.9));
  CHECK(!fitMinimal(PrimitiveType::Cone, line, up, 0.1, 0.9));
}

TEST(LeastSquaresFitsRecoverNoisyPrimitives)
{
  // vertices of each generated primitive, with noise of 0.1% of the diagonal, refit from a
  // start that is off by 5 degrees and 5%
  Part part = blockWithFeatures(0.1, 48);
  const double sigma = 0.001 * part.diagonal() / std::sqrt(3.0);
  addNoise(part, sigma, 3);
  std::vector<std::vector<int>> vertices(part.primitives.size());
  for (std::size_t f = 0; f < part.faces.size(); ++f)
    for (int v : part.faces[f])
      vertices[part.truth[f]].push_back(v);
  for (std::size_t label = 0; label < part.primitives.size(); ++label)
  {
    std::sort(vertices[label].begin(), vertices[label].end());
    vertices[label].erase(std::unique(vertices[label].begin(), vertices[label].end()), vertices[label].end());
    const Primitive& truth = part.primitives[label];
    Primitive start = truth;
    start.axis = Eigen::AngleAxisd(5 * M_PI / 180, Vec3(1, 1, 0).normalized()) * truth.axis;
    start.radius *= 1.05;
    start.setAngle(1.05 * truth.angle);
    start.center += Vec3(0.02, -0.01, 0.01);
    const Primitive fit = fitLeastSquares(start, part.points, vertices[label]);
    CHECK(axisAngle(fit.axis, truth.axis) < 0.5 || truth.type == PrimitiveType::Sphere);
    CHECK(std::abs(fit.radius - truth.radius) <= 0.005 * truth.radius);
    CHECK(std::abs(fit.angle - truth.angle) <= 0.5 * M_PI / 180);
  }
}

TEST(ForwardSearchStopsBeforeOutliers)
{
  // a noisy plane (sigma 1e-3) with 5% of the points 6e-3 .. 9e-3 off it, all within the
  // RANSAC band of 1e-2: the forward search keeps the plane's points and drops the others
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0, 1e-3);
  std::uniform_real_distribution<double> uniform(0, 1);
  PointList points;
  std::vector<Vec3> normals(2000, Vec3::UnitZ());
  std::vector<int> candidates;
  for (int i = 0; i < 2000; ++i)
  {
    const bool outlier = i % 20 == 0;
    const double z = outlier ? 6e-3 + 3e-3 * uniform(random) : noise(random);
    points.push_back(Vec3(uniform(random), uniform(random), z));
    candidates.push_back(i);
  }
  const Primitive start = syntheticparts::plane(Vec3(0.02, 0, 1), Vec3(0.5, 0.5, 0.003));
  ForwardSearchSettings settings;
  settings.floor = 1e-3;
  settings.cosAlpha = std::cos(0.3);
  const ForwardSearchResult result = forwardSearch(start, points, normals, candidates, settings);
  long outliers = 0;
  for (int i : result.members)
    outliers += i % 20 == 0;
  std::printf("members %zu, outliers among them %ld, rms %.2e\n", result.members.size(), outliers, result.rmsDistance);
  CHECK(outliers == 0);
  CHECK(result.members.size() >= 1880); // of the 1900 plane points, at most a 4 sigma tail lost
  CHECK(axisAngle(result.shape.axis, Vec3::UnitZ()) < 0.1);
  CHECK(result.rmsDistance < 1.2e-3);
}

TEST(CleanPartIsSegmented)
{
  const Part part = blockWithFeatures(0.05, 64);
  checkQuality(part, detect(part));
}

TEST(NoisyPartIsSegmented)
{
  // noise of 0.1% of the diagonal: the cylinders are found too
  Part part = blockWithFeatures(0.05, 64);
  addNoise(part, 0.001 * part.diagonal() / std::sqrt(3.0), 11);
  checkQuality(part, detect(part));
}

// Issue 11: a part of separate primitives (SyntheticParts.h) with vertex noise of the given
// fraction of the diagonal comes out whole: every generated primitive is one detected primitive
// of its type that holds >= 95% of its faces (the bound), within checkQuality's bounds.
// Legs of 0.04 are 5 times the largest noise of the issue (0.1% of the diagonal of about 7.9);
// the noise and the detection have their own seeds.
namespace
{
// The share of each generated primitive's faces that its matched detected primitive (of its
// type, rightFraction) holds.
std::vector<double> wholeShares(const Part& part, const Detection& d)
{
  std::map<int, int> match;
  rightFraction(part, d.found, match);
  const std::vector<int> assigned = assignedPrimitives(part, d.found);
  std::vector<long> faces(part.primitives.size(), 0), held(part.primitives.size(), 0);
  for (std::size_t f = 0; f < part.faces.size(); ++f)
  {
    const int truth = part.truth[f];
    ++faces[truth];
    held[truth] += match.count(truth) && assigned[f] == match[truth];
  }
  std::vector<double> shares;
  for (std::size_t truth = 0; truth < part.primitives.size(); ++truth)
    shares.push_back(static_cast<double>(held[truth]) / static_cast<double>(faces[truth]));
  return shares;
}

void checkWholeWithNoise(double level, double legs = 0.04, unsigned noiseSeed = 1, std::uint64_t detectSeed = 0)
{
  Part part = separatePrimitives(legs);
  addNoise(part, level * part.diagonal() / std::sqrt(3.0), noiseSeed);
  const Detection d = detect(part, detectSeed);
  checkQuality(part, d);
  const std::vector<double> shares = wholeShares(part, d);
  for (std::size_t truth = 0; truth < part.primitives.size(); ++truth)
  {
    std::printf("  %-8s %5ld faces, %.2f%% in one primitive\n", primitiveTypeName(part.primitives[truth].type),
      static_cast<long>(std::count(part.truth.begin(), part.truth.end(), static_cast<int>(truth))), 100 * shares[truth]);
    CHECK(shares[truth] >= 0.95);
  }
}
}

TEST(SeparatePrimitivesWithNoiseOf0_01PercentAreWhole)
{
  checkWholeWithNoise(0.0001);
}

TEST(SeparatePrimitivesWithNoiseOf0_05PercentAreWhole)
{
  checkWholeWithNoise(0.0005);
}

TEST(SeparatePrimitivesWithNoiseOf0_1PercentAreWhole)
{
  checkWholeWithNoise(0.001);
  checkWholeWithNoise(0.001, 0.04, 8, 4); // a box face that a cone of a far apex fits closer than the plane
}

TEST(SeparatePrimitivesWithNoiseOf0_3PercentAreWhole)
{
  // legs of 0.12: 8.8 times the noise's deviation per coordinate, the ratio of the 0.1% test's
  // legs of 0.04 (issue 31 asks for 0.3% as well); four noise and detection seeds
  for (unsigned seed = 1; seed <= 4; ++seed)
    checkWholeWithNoise(0.003, 0.12, seed, seed);
}

TEST(CoarseSeparatePrimitivesAreWhole)
{
  checkWholeWithNoise(0.0001, 0.1, 1, 3);
  checkWholeWithNoise(0.0002, 0.1, 4);
  // a box face whose noise a cone of a far apex fits closer than the plane
  checkWholeWithNoise(0.001, 0.1, 4, 3);
}

// Issue 57: primitives meshed the usual way (usualPrimitives: a UV sphere with fans at its
// poles, a cone with a fan at its apex, caps with fans at their centers) come out whole at every
// noise level from 0 to 0.3% of the diagonal in steps of 0.025%: each one detected primitive of
// its type holding >= 95% of its faces (the bound). The fans' thin triangles tilt with
// the noise by up to 90 degrees; the other faces, of legs h, by about 2 sigma / h RMS (sigma the
// noise per coordinate). Legs are at least 5 sigma at 0.3% (22 degrees RMS: 45% of the faces
// beyond the normal threshold of 20): 7.3 sigma for legs 0.1 on a diagonal of 7.9, 5.1 for legs
// 0.08 turned (diagonal 9.1), 6.5 and 7.8 for legs 0.1 and 0.12 on 8.9. Every level has its own
// noise and detection seeds.
namespace
{
Part turned(Part part, double angle, const Vec3& axis)
{
  rotate(part, Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix());
  return part;
}

Part subdivided(Part part)
{
  subdivide(part);
  return part;
}

// Every primitive one detected primitive holding >= 95% of its faces at every level (the least
// share of each type printed).
void checkWholeAtEveryLevel(const char* name, const Part& tessellation, unsigned seed)
{
  std::printf("%s: %zu faces\n  level    Plane Cylinder   Sphere     Cone\n", name, tessellation.faces.size());
  for (int k = 0; k <= 12; ++k)
  {
    const double level = 0.00025 * k;
    Part part = tessellation;
    addNoise(part, level * part.diagonal() / std::sqrt(3.0), seed + k);
    const Detection d = detect(part, seed + k);
    const std::vector<double> shares = wholeShares(part, d);
    std::array<double, 4> least{ 1, 1, 1, 1 };
    for (std::size_t truth = 0; truth < shares.size(); ++truth)
    {
      double& l = least[static_cast<int>(part.primitives[truth].type)];
      l = std::min(l, shares[truth]);
      CHECK(shares[truth] >= 0.95);
    }
    std::printf("%6.3f%% %7.2f%% %7.2f%% %7.2f%% %7.2f%%\n", 100 * level, 100 * least[0], 100 * least[1], 100 * least[2], 100 * least[3]);
  }
}
}

TEST(UsualTessellationIsWholeAtEveryNoiseLevel)
{
  checkWholeAtEveryLevel("open cylinder and cone, legs 0.1", usualPrimitives(0.1, false), 100);
}

TEST(TurnedTessellationWithCapsIsWholeAtEveryNoiseLevel)
{
  checkWholeAtEveryLevel("caps, legs 0.08, turned", turned(usualPrimitives(0.08, true), 0.9, Vec3(1, 2, 3)), 200);
}

TEST(SubdividedTessellationIsWholeAtEveryNoiseLevel)
{
  // midpoint subdivision: each triangle of legs 0.2 in four, a fan's in a smaller fan and a ring
  checkWholeAtEveryLevel(
    "caps, legs 0.2 subdivided once, turned", turned(subdivided(usualPrimitives(0.2, true)), 2.2, Vec3(-2, 1, 1)), 300);
}

TEST(CoarserTessellationIsWholeAtEveryNoiseLevel)
{
  checkWholeAtEveryLevel("caps, legs 0.12, turned", turned(usualPrimitives(0.12, true), 2.2, Vec3(-2, 1, 1)), 400);
}

TEST(SamplesWithinTheToleranceJoinTheirPrimitive)
{
  // an exact plane of 40 x 40 samples with a patch of six samples raised by half of epsilon:
  // beyond the forward search's floor (epsilon / 4), within RANSAC's tolerance; too few for a
  // primitive of their own. They join the plane, whose fit stays the one to the exact samples.
  RansacParameters p;
  p.epsilon = 0.01;
  p.clusterEpsilon = 0.05; // twice the grid spacing: the samples are connected
  p.normalThreshold = 20 * M_PI / 180;
  p.minimumSupport = 10;
  PointList points;
  for (int a = 0; a < 40; ++a)
    for (int b = 0; b < 40; ++b)
    {
      const bool raised = a >= 20 && a < 23 && b >= 20 && b < 22;
      points.emplace_back(a / 39.0, b / 39.0, raised ? p.epsilon / 2 : 0.0);
    }
  const std::vector<DetectedPrimitive> found = detectPrimitives(points, std::vector<Vec3>(points.size(), Vec3::UnitZ()), p);
  CHECK(found.size() == 1);
  if (found.size() == 1)
  {
    CHECK(found[0].members.size() == points.size());
    CHECK(found[0].shape.type == PrimitiveType::Plane && std::abs(found[0].shape.axis.z()) == 1.0);
    CHECK(std::abs(found[0].shape.offset) < 1e-15); // the fit to the exact samples: round-off of z = 0
    CHECK_NEAR(found[0].maxDistance, p.epsilon / 2, 1e-15);
  }
}

TEST(SameSeedSameResultWithAnyThreadCount)
{
  Part part = blockWithFeatures(0.1, 48);
  addNoise(part, 0.001 * part.diagonal() / std::sqrt(3.0), 2);
  omp_set_num_threads(1);
  const Detection serial = detect(part, 7);
  omp_set_num_threads(2);
  const Detection parallel = detect(part, 7), again = detect(part, 7), other = detect(part, 8);
  auto same = [](const Detection& a, const Detection& b) {
    if (a.found.size() != b.found.size())
      return false;
    for (std::size_t i = 0; i < a.found.size(); ++i)
      if (a.found[i].members != b.found[i].members || a.found[i].shape.axis != b.found[i].shape.axis)
        return false;
    return true;
  };
  CHECK(same(serial, parallel));
  CHECK(same(parallel, again));
  CHECK(!same(parallel, other)); // the seed matters
  // the benchmark's part of 104k faces: primitives of more than ParallelSamples faces, whose
  // loops (forward search, fits, scoring of large subsets) run on both threads
  const Part large = blockWithFeatures(0.03, 96);
  omp_set_num_threads(1);
  const Detection largeSerial = detect(large, 3);
  omp_set_num_threads(2);
  CHECK(same(largeSerial, detect(large, 3)));
}

TEST(BadInputIsRejectedOrSkipped)
{
  const RansacParameters p = defaults(1.0);
  CHECK_THROWS(detectPrimitives({ Vec3(0, 0, std::nan("")) }, { Vec3::UnitZ() }, p), InvalidInputException);
  CHECK_THROWS(detectPrimitives({ Vec3(0, 0, 0) }, {}, p), InvalidInputException);
  RansacParameters bad = p;
  bad.epsilon = 0;
  CHECK_THROWS(detectPrimitives({ Vec3(0, 0, 0) }, { Vec3::UnitZ() }, bad), InvalidInputException);
  bad = p;
  bad.probability = 1;
  CHECK_THROWS(detectPrimitives({ Vec3(0, 0, 0) }, { Vec3::UnitZ() }, bad), InvalidInputException);
  CHECK(detectPrimitives({}, {}, p).empty());
  // faces: out of range and NaN vertices are errors; degenerate faces (two vertices, zero area)
  // get NaN normals and are left out of every primitive
  const PointList square = { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(2, 0, 0) };
  CHECK_THROWS(faceSamples(square, { { 0, 1, 9 } }), InvalidInputException);
  CHECK_THROWS(faceSamples({ Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(std::nan(""), 1, 0) }, { { 0, 1, 2 } }), InvalidInputException);
  const FaceSamples s = faceSamples(square, { { 0, 1, 2, 3 }, { 0, 1 }, { 0, 1, 4 }, { 0, 0, 2 } });
  CHECK((s.barycenters[0] - Vec3(0.5, 0.5, 0)).norm() < 1e-15);
  CHECK_NEAR(s.areas[0], 1.0, 1e-15);
  CHECK(std::abs(s.normals[0].z()) == 1.0);
  for (int f = 1; f < 4; ++f)
    CHECK(!s.normals[f].allFinite() && s.areas[f] == 0);
  // a mesh of only degenerate faces finds nothing (and does not fail)
  CHECK(detectPrimitives(s.barycenters, { s.normals[1], s.normals[1], s.normals[1], s.normals[1] }, p).empty());
  // the faces given with the samples: one per sample, vertex indices in range, finite vertices
  const PointList one = { Vec3(0.5, 0.5, 0) };
  const SampleFaces outOfRange{ { { 0, 1, 9 } }, square }, tooFew{ {}, square },
    nanVertex{ { { 0, 1, 2 } }, { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(std::nan(""), 1, 0) } };
  for (const SampleFaces* faces : { &outOfRange, &tooFew, &nanVertex })
    CHECK_THROWS(detectPrimitives(one, { Vec3::UnitZ() }, p, faces), InvalidInputException);
}

TEST_MAIN
