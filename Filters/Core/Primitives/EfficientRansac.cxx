#include "Primitives/EfficientRansac.h"

#include "Common/BoundingBox.h"
#include "Common/KeySort.h"
#include "Common/ZOrder.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <random>

namespace mlsdeform
{
namespace
{
// Bits of the Morton code per axis: the finest octree cell is 1/1024 of the bounding box.
constexpr int MortonBits = 10;
// Samples in the first scoring subset; the next subsets double.
constexpr long FirstSubset = 256;
// Minimal sets drawn between two decisions.
constexpr int DrawsPerBatch = 200;
// A search that draws this many minimal sets stops whatever it found.
constexpr long MaximumDraws = 20000000;
// Candidates kept between batches, the best estimates.
constexpr std::size_t KeptCandidates = 1000;
// Width of the confidence interval of an estimated score, in standard deviations.
constexpr double ConfidenceWidth = 2;
// Samples left within this many epsilon of a primitive may be the ends of its surface
// (fitMinimaxWithEnds); the fandisk's lie within 1.24.
constexpr double EndsWidth = 2;

// The octree of the samples, implicit in their Morton order (Schnabel et al. section 4.3).
class MortonOctree
{
public:
  MortonOctree(const PointList& points, const std::vector<int>& valid)
  {
    PointList used;
    for (int i : valid)
    {
      used.push_back(points[i]);
    }
    Box = boundingBox(used);
    const BoundingBox& box = Box;
    const double size = std::max(box.size().maxCoeff(), 1e-300);
    Code.assign(points.size(), 0);
    for (int i : valid)
    {
      const Vec3 t = (points[i] - box.lower) / size * ((1 << MortonBits) - 1);
      Code[i] = mortonCode(static_cast<std::uint64_t>(t.x()), static_cast<std::uint64_t>(t.y()), static_cast<std::uint64_t>(t.z()));
    }
    std::vector<std::pair<std::uint64_t, long>> byCode;
    for (int i : valid)
    {
      byCode.emplace_back(Code[i], i);
    }
    sortByKey(byCode, 3 * MortonBits);
    for (const auto& [code, i] : byCode)
    {
      Order.push_back(static_cast<int>(i));
      Sorted.push_back(code);
    }
  }

  /// The samples in the cell of the given level (0: the root) that contains sample i, as a
  /// range [first, last) of order().
  std::pair<long, long> cell(int i, int level) const
  {
    const int shift = 3 * (MortonBits - level);
    const std::uint64_t lower = (Code[i] >> shift) << shift, upper = lower + (std::uint64_t(1) << shift);
    const long first = std::lower_bound(Sorted.begin(), Sorted.end(), lower) - Sorted.begin();
    const long last = std::lower_bound(Sorted.begin(), Sorted.end(), upper) - Sorted.begin();
    return { first, last };
  }
  const std::vector<int>& order() const { return Order; }
  /// The bounding box of the samples.
  const BoundingBox& box() const { return Box; }

private:
  BoundingBox Box;
  std::vector<std::uint64_t> Code;
  std::vector<int> Order;
  std::vector<std::uint64_t> Sorted;
};

// The connected components of the samples (indices into points): samples whose cells of size
// clusterEpsilon touch (26-neighbourhood) are connected (Schnabel et al. section 4.4), and so are
// faces that share a vertex when faces are given (a coarse mesh's faces can be farther apart
// than clusterEpsilon and still be one surface). Returns the component of every sample position,
// named by one of its positions.
std::vector<long> components(const PointList& points, const std::vector<int>& samples, double clusterEpsilon,
  const std::vector<std::vector<int>>* faces, std::vector<int>& vertexOwner)
{
  if (samples.empty())
  {
    return {};
  }
  Vec3 lower = points[samples[0]], upper = lower;
  for (int i : samples)
  {
    lower = lower.cwiseMin(points[i]);
    upper = upper.cwiseMax(points[i]);
  }
  // cells 1 .. n per axis and an empty layer on either side (the neighbours of every cell have
  // keys), at most 2^21 - 1 per axis (the key fits 63 bits)
  std::array<std::uint64_t, 3> cells;
  for (int d = 0; d < 3; ++d)
  {
    cells[d] = static_cast<std::uint64_t>(std::min(std::floor((upper[d] - lower[d]) / clusterEpsilon), double(1 << 21) - 4)) + 3;
  }
  auto key = [&](std::uint64_t x, std::uint64_t y, std::uint64_t z) { return (x * cells[1] + y) * cells[2] + z; };
  const long n = static_cast<long>(samples.size());
  std::vector<std::pair<std::uint64_t, long>> byCell(n); // (cell key, sample position)
  for (long a = 0; a < n; ++a)
  {
    const Vec3 t = (points[samples[a]] - lower) / clusterEpsilon;
    std::array<std::uint64_t, 3> cell;
    for (int d = 0; d < 3; ++d)
    {
      cell[d] = std::min(static_cast<std::uint64_t>(std::min(t[d], double(cells[d]))) + 1, cells[d] - 2);
    }
    byCell[a] = { key(cell[0], cell[1], cell[2]), a };
  }
  sortByKey(byCell, keyBits(cells[0] * cells[1] * cells[2]));
  std::vector<long> parent(n);
  std::iota(parent.begin(), parent.end(), 0L);
  auto find = [&](long a) {
    while (parent[a] != a)
    {
      a = parent[a] = parent[parent[a]];
    }
    return a;
  };
  auto unite = [&](long a, long b) { parent[find(a)] = find(b); };
  // the occupied cells, each represented by its first sample; the samples of a cell are one
  std::vector<std::uint64_t> cellKey;
  std::vector<long> representative;
  for (const auto& [k, a] : byCell)
  {
    if (cellKey.empty() || cellKey.back() != k)
    {
      cellKey.push_back(k);
      representative.push_back(a);
    }
    else
    {
      unite(a, representative.back());
    }
  }
  // cells that touch (26-neighbourhood) are one: each pair is looked up once, from the cell of
  // the smaller key, at the 13 offsets that add to its key. A neighbour's key grows with the
  // cell's, so each offset's search goes on from where the previous cell's stopped.
  std::vector<std::uint64_t> offsets;
  for (std::uint64_t dx = 0; dx <= 1; ++dx)
    for (std::uint64_t dy = 1 - dx; dy <= 2; ++dy)
      for (std::uint64_t dz = (dx == 0 && dy == 1) ? 2 : 0; dz <= 2; ++dz)
      {
        offsets.push_back(key(1 + dx, dy, dz) - key(1, 1, 1));
      }
  std::vector<std::size_t> next(offsets.size(), 0);
  for (std::size_t c = 0; c < cellKey.size(); ++c)
  {
    for (std::size_t o = 0; o < offsets.size(); ++o)
    {
      const std::uint64_t neighbour = cellKey[c] + offsets[o];
      std::size_t& j = next[o];
      while (j < cellKey.size() && cellKey[j] < neighbour)
      {
        ++j;
      }
      if (j < cellKey.size() && cellKey[j] == neighbour)
      {
        unite(representative[j], representative[c]);
      }
    }
  }
  if (faces)
  {
    for (long a = 0; a < n; ++a)
    {
      for (int v : (*faces)[samples[a]])
      {
        if (vertexOwner[v] >= 0)
        {
          unite(a, vertexOwner[v]);
        }
        vertexOwner[v] = static_cast<int>(a);
      }
    }
    for (long a = 0; a < n; ++a)
    {
      for (int v : (*faces)[samples[a]])
      {
        vertexOwner[v] = -1;
      }
    }
  }
  std::vector<long> component(n);
  for (long a = 0; a < n; ++a)
  {
    component[a] = find(a);
  }
  return component;
}

// The largest connected component of the samples (components).
std::vector<int> largestComponent(const PointList& points, const std::vector<int>& samples, double clusterEpsilon,
  const std::vector<std::vector<int>>* faces, std::vector<int>& vertexOwner)
{
  if (samples.size() < 2)
  {
    return samples;
  }
  const std::vector<long> component = components(points, samples, clusterEpsilon, faces, vertexOwner);
  std::vector<long> size(samples.size(), 0);
  for (long c : component)
  {
    ++size[c];
  }
  const long largest = std::max_element(size.begin(), size.end()) - size.begin();
  std::vector<int> largestSamples;
  for (std::size_t a = 0; a < samples.size(); ++a)
  {
    if (component[a] == largest)
    {
      largestSamples.push_back(samples[a]);
    }
  }
  return largestSamples;
}

// Kasa's algebraic sphere fit ("A circle fitting procedure and its error analysis", IEEE
// Transactions on Instrumentation and Measurement 25(1), 1976): |x|^2 = 2 c . x + d by linear
// least squares (about the centroid), radius sqrt(d + |c|^2). A start for the geometric fit.
Primitive algebraicSphere(const PointList& points, const std::vector<int>& subset)
{
  Vec3 mean = Vec3::Zero();
  for (int i : subset)
  {
    mean += points[i];
  }
  mean /= static_cast<double>(subset.size());
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  for (int i : subset)
  {
    const Vec3 x = points[i] - mean;
    const Eigen::Vector4d row(2 * x.x(), 2 * x.y(), 2 * x.z(), 1);
    A += row * row.transpose();
    b += row * x.squaredNorm();
  }
  const Eigen::Vector4d solution = A.ldlt().solve(b);
  Primitive sphere;
  sphere.type = PrimitiveType::Sphere;
  sphere.center = mean + solution.head<3>();
  sphere.radius = std::sqrt(std::max(0.0, solution[3] + solution.head<3>().squaredNorm()));
  return sphere;
}

struct Candidate
{
  Primitive shape;
  std::array<int, 3> samples;
  int level = 0;
  int subsets = 0;          // evaluated subsets
  std::vector<int> hits;    // the available compatible samples in them
  double estimate = 0, lower = 0, upper = 0;
};

class Search
{
public:
  Search(const PointList& points, const std::vector<Vec3>& normals, const SampleFaces* mesh, const RansacParameters& p,
    const std::vector<int>& valid)
    : Points(points)
    , Normals(normals)
    , Mesh(mesh)
    , P(p)
    , CosAlpha(std::cos(p.normalThreshold))
    , Octree(points, valid)
    , Valid(valid)
    , Available(points.size(), 0)
    , Random(p.seed)
  {
    for (int i : valid)
    {
      Available[i] = 1;
    }
    Diagonal = Octree.box().size().norm();
    Refinement.floor = P.epsilon / 4;
    Refinement.cosAlpha = CosAlpha;
    Refinement.ceiling = P.epsilon;
    if (Mesh)
    {
      int vertices = 0;
      for (int i : valid)
      {
        for (int v : Mesh->faces[i])
        {
          vertices = std::max(vertices, v + 1);
        }
      }
      VertexOwner.assign(vertices, -1);
    }
    // levels 0 .. L-1, the finest with about four samples per cell
    const double perCell = std::max(1.0, static_cast<double>(valid.size()) / 4);
    Levels = std::clamp(static_cast<int>(std::ceil(std::log(perCell) / std::log(8.0))), 1, MortonBits);
    LevelDraws.assign(Levels, 0);
    LevelScore.assign(Levels, 0);
    for (PrimitiveType type : { PrimitiveType::Plane, PrimitiveType::Cylinder, PrimitiveType::Sphere, PrimitiveType::Cone })
    {
      const bool enabled = type == PrimitiveType::Plane ? p.planes : type == PrimitiveType::Cylinder ? p.cylinders
        : type == PrimitiveType::Sphere                  ? p.spheres
                                                         : p.cones;
      if (enabled)
      {
        Types.push_back(type);
      }
    }
    // the scoring subsets: ranges of one random order of the samples, from which the extracted
    // ones drop out (what stays of a random sample is a random sample of what stays)
    Order = valid;
    std::shuffle(Order.begin(), Order.end(), Random);
    for (long end = 0, size = FirstSubset; end < static_cast<long>(Order.size()); size *= 2)
    {
      end = std::min(static_cast<long>(Order.size()), end + size);
      SubsetEnd.push_back(end);
    }
    for (int i : Order)
    {
      OrderPoints.push_back(Points[i]);
      OrderNormals.push_back(Normals[i]);
    }
    Remaining = valid;
  }

  /// The primitives found; again: search the samples they leave once more (searchLeftover).
  std::vector<DetectedPrimitive> run(const Progress& progress, bool again = true)
  {
    std::vector<DetectedPrimitive> found;
    const double total = static_cast<double>(Remaining.size());
    while (static_cast<long>(Remaining.size()) >= P.minimumSupport && !Types.empty() && Draws < MaximumDraws)
    {
      const bool searched = detectionProbability(P.minimumSupport) >= P.probability;
      if (!searched)
      {
        drawBatch(); // once a shape of minimumSupport samples would have been found, only the candidates left are tried
      }
      Candidate* best = refineBest();
      if (best && best->estimate >= P.minimumSupport && detectionProbability(best->estimate) >= P.probability)
      {
        DetectedPrimitive primitive;
        std::vector<int> component;
        if (extract(*best, primitive, component))
        {
          found.push_back(std::move(primitive));
          removeMembers(found.back().members);
          progress.report(1 - Remaining.size() / total);
        }
        else
        {
          dropFailed(static_cast<std::size_t>(best - Candidates.data()), component);
        }
      }
      else if (searched)
      {
        break;
      }
    }
    splitIntoPlanes(found);
    settle(found);
    if (again)
    {
      searchLeftover(found);
    }
    return found;
  }

private:
  // The face of every sample, or none.
  const std::vector<std::vector<int>>* faces() const { return Mesh ? &Mesh->faces : nullptr; }

  // The samples in no primitive, increasing.
  std::vector<int> unheld(const std::vector<DetectedPrimitive>& found) const
  {
    std::vector<char> held(Points.size(), 0);
    for (const DetectedPrimitive& primitive : found)
    {
      for (int i : primitive.members)
      {
        held[i] = 1;
      }
    }
    std::vector<int> left;
    std::copy_if(Valid.begin(), Valid.end(), std::back_inserter(left), [&](int i) { return !held[i]; });
    return left;
  }

  // The search once more on the samples in no primitive, as the stopping rule assumes of the
  // samples left: minimal sets drawn among them alone find the primitives there that the draws
  // over all samples missed (on couplingdown, seeds differed by up to 10 points of coverage).
  // What it finds joins the others, and settle decides again.
  void searchLeftover(std::vector<DetectedPrimitive>& found) const
  {
    const std::vector<int> left = unheld(found);
    if (static_cast<int>(left.size()) < P.minimumSupport)
    {
      return;
    }
    Search search(Points, Normals, Mesh, P, left);
    std::vector<DetectedPrimitive> more = search.run({}, false);
    if (!more.empty())
    {
      std::move(more.begin(), more.end(), std::back_inserter(found));
      settle(found);
    }
  }

  // 1 - (1 - n / (N L 2^(k-1)))^T for minimal sets of k = 3 samples (Schnabel et al. eq. 4)
  double detectionProbability(double n) const
  {
    const double N = static_cast<double>(Remaining.size());
    const double single = std::min(1.0, n / (N * Levels * 4));
    return 1 - std::pow(1 - single, static_cast<double>(Draws));
  }

  // The samples in the subsets before subset k.
  long subsetStart(int k) const { return k == 0 ? 0 : SubsetEnd[k - 1]; }

  // Evaluates the candidate on its next subset, and on more while fewer than FirstSubset of
  // its evaluated samples are available (extractions thin the subsets out).
  void evaluateNextSubset(Candidate& c) const
  {
    do
    {
      const long begin = subsetStart(c.subsets), n = SubsetEnd[c.subsets] - begin;
      std::vector<char> hit(n);
#pragma omp parallel for schedule(static) if (n >= ParallelSamples)
      for (long a = 0; a < n; ++a)
      {
        hit[a] = c.shape.compatible(OrderPoints[begin + a], OrderNormals[begin + a], P.epsilon, CosAlpha);
      }
      for (long a = 0; a < n; ++a)
      {
        if (hit[a])
        {
          c.hits.push_back(Order[begin + a]);
        }
      }
      ++c.subsets;
    } while (subsetStart(c.subsets) < FirstSubset && !fullyEvaluated(c));
    estimate(c);
  }

  // Expected score N c / m of a candidate with c hits among the m available samples of its
  // evaluated subsets, with a normal approximation of the hypergeometric spread.
  void estimate(Candidate& c) const
  {
    const double N = static_cast<double>(Remaining.size()), m = static_cast<double>(subsetStart(c.subsets));
    const double hits = static_cast<double>(c.hits.size());
    if (!(m > 0))
    {
      c.estimate = c.lower = c.upper = 0; // every sample gone: nothing left to score
      return;
    }
    const double f = hits / m, fSpread = (hits + 1.0) / (m + 2);
    const double spread = N * std::sqrt(fSpread * (1 - fSpread) / m * std::max(0.0, (N - m) / std::max(1.0, N - 1)));
    c.estimate = N * f;
    c.lower = c.estimate - ConfidenceWidth * spread;
    c.upper = c.estimate + ConfidenceWidth * spread;
  }

  // Spheres and cylinders wider than the samples' bounding box are planes or free-form patches
  // within epsilon, cones must keep their angle range (MinimumConeAngle).
  bool plausible(const Primitive& s) const
  {
    switch (s.type)
    {
      case PrimitiveType::Sphere:
      case PrimitiveType::Cylinder:
        return s.radius <= Diagonal;
      case PrimitiveType::Cone:
        return s.angle >= MinimumConeAngle && s.angle <= M_PI / 2 - MinimumConeAngle;
      case PrimitiveType::Plane:
        break;
    }
    return true;
  }

  bool fullyEvaluated(const Candidate& c) const { return c.subsets == static_cast<int>(SubsetEnd.size()); }

  // Draws minimal sets (serially, from the seeded generator) and scores their candidates on the
  // first subset (in parallel).
  void drawBatch()
  {
    std::vector<double> weight(Levels);
    double sum = 0;
    for (int l = 0; l < Levels; ++l)
    {
      sum += LevelDraws[l] > 0 ? LevelScore[l] / LevelDraws[l] : 0;
    }
    for (int l = 0; l < Levels; ++l)
    {
      const double learned = sum > 0 && LevelDraws[l] > 0 ? LevelScore[l] / LevelDraws[l] / sum : 1.0 / Levels;
      weight[l] = 0.9 * learned + 0.1 / Levels;
    }
    std::discrete_distribution<int> pickLevel(weight.begin(), weight.end());
    std::uniform_int_distribution<long> pickRemaining(0, static_cast<long>(Remaining.size()) - 1);
    const std::size_t first = Candidates.size();
    for (int draw = 0; draw < DrawsPerBatch; ++draw)
    {
      ++Draws;
      const int level = pickLevel(Random);
      ++LevelDraws[level];
      std::array<int, 3> s;
      s[0] = Remaining[pickRemaining(Random)];
      const auto [begin, end] = Octree.cell(s[0], level);
      if (end - begin < 3)
      {
        continue;
      }
      std::uniform_int_distribution<long> pickInCell(begin, end - 1);
      int found = 1;
      for (int attempt = 0; attempt < 20 && found < 3; ++attempt)
      {
        const int i = Octree.order()[pickInCell(Random)];
        if (Available[i] && std::find(s.begin(), s.begin() + found, i) == s.begin() + found)
        {
          s[found++] = i;
        }
      }
      if (found < 3)
      {
        continue;
      }
      const Vec3 p[3] = { Points[s[0]], Points[s[1]], Points[s[2]] };
      const Vec3 n[3] = { Normals[s[0]], Normals[s[1]], Normals[s[2]] };
      for (PrimitiveType type : Types)
      {
        const std::optional<Primitive> shape = fitMinimal(type, p, n, P.epsilon, CosAlpha);
        if (shape && plausible(*shape))
        {
          Candidate c;
          c.shape = *shape;
          c.samples = s;
          c.level = level;
          Candidates.push_back(c);
        }
      }
    }
    scoreFrom(first);
    for (std::size_t c = first; c < Candidates.size(); ++c)
    {
      LevelScore[Candidates[c].level] += Candidates[c].estimate;
    }
    if (Candidates.size() > 2 * KeptCandidates)
    {
      // the candidates far down the ranking will not be extracted before new draws replace them
      std::stable_sort(Candidates.begin(), Candidates.end(), [](const Candidate& a, const Candidate& b) { return a.estimate > b.estimate; });
      Candidates.resize(KeptCandidates);
    }
  }

  void scoreFrom(std::size_t first)
  {
    const long count = static_cast<long>(Candidates.size() - first);
#pragma omp parallel for schedule(dynamic, 16)
    for (long c = 0; c < count; ++c)
    {
      evaluateNextSubset(Candidates[first + c]);
    }
  }

  // The candidate with the best estimate, its score refined on more subsets until its interval
  // lies above every other candidate's (section 4.5), or until its score is exact (then the
  // others, expected lower, are not evaluated in full one after another).
  Candidate* refineBest()
  {
    while (!Candidates.empty())
    {
      auto byEstimate = [](const Candidate& a, const Candidate& b) { return a.estimate < b.estimate; };
      Candidate& best = *std::max_element(Candidates.begin(), Candidates.end(), byEstimate);
      Candidate* challenger = nullptr;
      for (Candidate& c : Candidates)
      {
        if (&c != &best && c.upper > best.lower && (!challenger || c.upper > challenger->upper))
        {
          challenger = &c;
        }
      }
      if (!challenger || fullyEvaluated(best))
      {
        return &best;
      }
      if (!fullyEvaluated(best))
      {
        evaluateNextSubset(best);
      }
      else if (!fullyEvaluated(*challenger))
      {
        evaluateNextSubset(*challenger);
      }
      else
      {
        return &best;
      }
    }
    return nullptr;
  }

  std::vector<int> compatibleComponent(const Primitive& shape) const
  {
    const long n = static_cast<long>(Remaining.size());
    std::vector<char> flag(n);
#pragma omp parallel for schedule(static) if (n >= ParallelSamples)
    for (long a = 0; a < n; ++a)
    {
      flag[a] = shape.compatible(Points[Remaining[a]], Normals[Remaining[a]], P.epsilon, CosAlpha);
    }
    std::vector<int> compatible; // increasing, as Remaining
    for (long a = 0; a < n; ++a)
    {
      if (flag[a])
      {
        compatible.push_back(Remaining[a]);
      }
    }
    return largestComponent(Points, compatible, P.clusterEpsilon, faces(), VertexOwner);
  }

  // Occam's razor by Schwarz's Bayesian information criterion ("Estimating the dimension of a
  // model", Annals of Statistics 6(2), 1978) for nested models on the n observations of a curved
  // primitive of k parameters (parameterCount): the least-squares plane explains them as well
  // unless n log(RSS_plane / RSS_curved) > (k - 3) log n (a cone of a far apex or a wide cylinder
  // lies within the tolerance of a noisy flat face and fits its noise a little closer). A
  // residual sum counts at least n (floor / jump)^2: below that deviation the forward search
  // tells no fit from another (exact samples of a flat face lie as exactly on a far cone).
  // The criterion assumes independent residuals (observations: with faces, the vertices of the
  // members' faces, both models fit to them). Its penalty also assumes a regular model, but a
  // plane is the limit of a cone or cylinder whose apex or axis recedes anywhere, and the best of
  // those bends fits noise closer than k - 3 parameters would: a cone of 70 degrees fits the
  // vertices of a noisy box face with 9% less RSS, beyond the penalty, bending by 1.2 floors over
  // it. A bend within the band the forward search admits around a fit (admissionDistance of the
  // members' RMS distance: at least the floor, jump times the noise) tells no more than a
  // residual does, so the plane explains a curved primitive whose sagitta over its members is
  // less than that band.
  bool planeExplains(const Primitive& curved, const std::vector<int>& members) const
  {
    if (members.size() < 3)
    {
      return false; // no plane to compare with
    }
    if (sagitta(curved, members) < admissionDistance(Refinement, distanceStatistics(curved, Points, members).rms))
    {
      return true;
    }
    Primitive plane;
    plane.type = PrimitiveType::Plane;
    const std::vector<int> observed = observations(members);
    return simplerExplains(static_cast<double>(observed.size()), fitSquaredSum(plane, observed), 3, fitSquaredSum(curved, observed),
      parameterCount(curved.type));
  }

  // The observations of the members for Schwarz's criterion (planeExplains), indices into
  // observedPoints(): the vertices of their faces, each once, if faces are given, else the
  // samples. The criterion assumes independent residuals. Face barycenters are not: each averages
  // the noise of its vertices, which it shares with its neighbours, and a fan's faces all share
  // the noise of its center, which a flat cone with its apex there fits (a cap's fan: 40% less RSS
  // over its barycenters).
  std::vector<int> observations(const std::vector<int>& members) const
  {
    if (!Mesh)
    {
      return members;
    }
    std::vector<int> observed;
    for (int i : members)
    {
      observed.insert(observed.end(), Mesh->faces[i].begin(), Mesh->faces[i].end());
    }
    std::sort(observed.begin(), observed.end());
    observed.erase(std::unique(observed.begin(), observed.end()), observed.end());
    return observed;
  }

  const PointList& observedPoints() const { return Mesh ? Mesh->vertices : Points; }

  // The squared sum of the distances of the observations from the least-squares fit to them,
  // started from shape.
  double fitSquaredSum(const Primitive& shape, const std::vector<int>& observed) const
  {
    return squaredSum(fitLeastSquares(shape, observedPoints(), observed), observedPoints(), observed);
  }

  // The sagitta of a curved primitive over samples (extent^2 / (8 radius) for an arc): the width,
  // across their least-squares plane, of the points of its surface closest to the samples (their
  // feet; a sample closest to a cone's apex gets a point off the surface, which only widens it).
  double sagitta(const Primitive& curved, const std::vector<int>& samples) const
  {
    PointList feet;
    for (int i : samples)
    {
      Vec3 normal;
      const Vec3 step = curved.distance(Points[i], normal) * normal;
      const Vec3 inward = Points[i] - step, outward = Points[i] + step;
      feet.push_back(curved.distance(inward) <= curved.distance(outward) ? inward : outward);
    }
    std::vector<int> all(feet.size());
    std::iota(all.begin(), all.end(), 0);
    Primitive plane;
    plane.type = PrimitiveType::Plane;
    plane = fitLeastSquares(plane, feet, all);
    double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
    for (const Vec3& foot : feet)
    {
      const double height = plane.axis.dot(foot) - plane.offset;
      lowest = std::min(lowest, height);
      highest = std::max(highest, height);
    }
    return highest - lowest;
  }

  double squaredSum(const Primitive& shape, const PointList& points, const std::vector<int>& subset) const
  {
    return static_cast<double>(subset.size()) * std::pow(distanceStatistics(shape, points, subset).rms, 2);
  }

  // The least squared sum of distances that n samples count with: n (floor / jump)^2, the
  // forward search's floor (no model is told apart from another below it).
  double leastSquaredSum(double n) const
  {
    const double deviation = Refinement.floor / Refinement.jump;
    return n * deviation * deviation;
  }

  // Schwarz's criterion on n samples: a model of k parameters and residual sum of squares rss
  // against a richer one of K > k (or K <= k: then it must fit as well or better), both sums at
  // least n (floor / jump)^2 (planeExplains).
  bool simplerExplains(double n, double rss, int k, double richRss, int richK) const
  {
    const double least = leastSquaredSum(n);
    return n * std::log(std::max(least, rss) / std::max(least, richRss)) <= (richK - k) * std::log(n);
  }

  // The most planes that simplerExplains can prefer to the curved primitive on its members:
  // with their squared sum at its least, n (floor / jump)^2, that is 3 m <= k + n log(curved's
  // sum / least) / log n.
  long mostPlanes(const DetectedPrimitive& curved) const
  {
    const double n = static_cast<double>(curved.members.size()), least = leastSquaredSum(n);
    const double ratio = std::max(least, squaredSum(curved.shape, Points, curved.members)) / least;
    const double most = (parameterCount(curved.shape.type) + n * std::log(ratio) / std::log(n)) / 3;
    return std::max(1L, static_cast<long>(std::min(most, n)));
  }

  // A curved primitive tangent to several flat faces (a cone in the corner of two faces of a
  // box, found before either face's plane) holds strips of those faces within epsilon; its
  // members as a whole are no plane, so planeExplains keeps it, and the faces' remaining pieces
  // come out as other primitives, never one plane per face. The greedy extraction never
  // revisits it, so here planes are searched among its members (the same search, planes only,
  // the same seed): when they hold all but fewer than minimumSupport of them and explain them
  // as well by Schwarz's criterion (m planes: 3 m parameters), they replace it, and settle then
  // drops the pieces that the planes explain and merges the rest into them.
  void splitIntoPlanes(std::vector<DetectedPrimitive>& found) const
  {
    if (!P.planes)
    {
      return;
    }
    RansacParameters planesOnly = P;
    planesOnly.cylinders = planesOnly.spheres = planesOnly.cones = false;
    // the searches are independent: one thread each (their loops then run on it alone)
    const long count = static_cast<long>(found.size());
    std::vector<std::vector<DetectedPrimitive>> planesAmong(count);
#pragma omp parallel for schedule(dynamic, 1)
    for (long p = 0; p < count; ++p)
    {
      if (found[p].shape.type != PrimitiveType::Plane)
      {
        // planes that replace it are at most mostPlanes, so the largest holds a share of its
        // members: a search for that plane alone is short, and the whole search follows only
        // when it finds one (a truly curved primitive holds no plane of that size)
        RansacParameters largest = planesOnly;
        const long n = static_cast<long>(found[p].members.size()), most = mostPlanes(found[p]);
        largest.minimumSupport = static_cast<int>(std::max<long>(P.minimumSupport, (n - P.minimumSupport + most) / most));
        if (!Search(Points, Normals, Mesh, largest, found[p].members).run({}, false).empty())
        {
          planesAmong[p] = Search(Points, Normals, Mesh, planesOnly, found[p].members).run({});
        }
      }
    }
    std::vector<DetectedPrimitive> split;
    for (long p = 0; p < count; ++p)
    {
      DetectedPrimitive& primitive = found[p];
      if (primitive.shape.type != PrimitiveType::Plane)
      {
        std::vector<DetectedPrimitive>& planes = planesAmong[p];
        long held = 0;
        double planesSum = 0;
        for (const DetectedPrimitive& plane : planes)
        {
          held += static_cast<long>(plane.members.size());
          planesSum += squaredSum(plane.shape, Points, plane.members);
        }
        const long n = static_cast<long>(primitive.members.size());
        if (!planes.empty() && n - held < P.minimumSupport)
        {
          // the members no plane holds count with their distance from the curved primitive
          std::vector<char> inPlane(Points.size(), 0);
          for (const DetectedPrimitive& plane : planes)
          {
            for (int i : plane.members)
            {
              inPlane[i] = 1;
            }
          }
          std::vector<int> rest;
          for (int i : primitive.members)
          {
            if (!inPlane[i])
            {
              rest.push_back(i);
            }
          }
          planesSum += squaredSum(primitive.shape, Points, rest);
          if (simplerExplains(static_cast<double>(n), planesSum, 3 * static_cast<int>(planes.size()),
                squaredSum(primitive.shape, Points, primitive.members), parameterCount(primitive.shape.type)))
          {
            std::move(planes.begin(), planes.end(), std::back_inserter(split));
            continue;
          }
        }
      }
      split.push_back(std::move(primitive));
    }
    found = std::move(split);
  }

  // A candidate that fails holds no primitive of its type in the compatible component it was
  // refined on, which extract leaves in component. Candidates of that type drawn in it whose
  // compatible samples all lie in it would be refined on it again, and go with it (on a curved
  // patch that no plane fits, hundreds of plane candidates would fail one after another).
  void dropFailed(std::size_t failed, const std::vector<int>& component)
  {
    std::vector<char> inComponent(Points.size(), 0);
    for (int i : component)
    {
      inComponent[i] = 1;
    }
    auto inside = [&](const auto& samples) {
      return std::all_of(samples.begin(), samples.end(), [&](int i) { return inComponent[i] != 0; });
    };
    const PrimitiveType type = Candidates[failed].shape.type;
    std::vector<Candidate> kept;
    for (std::size_t c = 0; c < Candidates.size(); ++c)
    {
      const Candidate& candidate = Candidates[c];
      if (c != failed && !(candidate.shape.type == type && inside(candidate.samples) && inside(candidate.hits)))
      {
        kept.push_back(std::move(Candidates[c]));
      }
    }
    Candidates = std::move(kept);
  }

  // Refits the shape to its compatible component while that grows (twice at most: an inexact
  // candidate from noisy normals grows onto its surface), then the forward search refines it on
  // the component. False when the component is smaller than the minimum support.
  bool grow(Primitive shape, std::vector<int>& component, ForwardSearchResult& refined) const
  {
    component = compatibleComponent(shape);
    for (int pass = 0; pass < 2 && static_cast<int>(component.size()) >= P.minimumSupport; ++pass)
    {
      const Primitive refit = fitLeastSquares(shape, Points, component);
      if (!plausible(refit))
      {
        break;
      }
      std::vector<int> grown = compatibleComponent(refit);
      if (grown.size() < component.size())
      {
        break;
      }
      shape = refit;
      component = std::move(grown);
    }
    if (static_cast<int>(component.size()) < P.minimumSupport)
    {
      return false;
    }
    refined = forwardSearch(shape, Points, Normals, component, Refinement);
    return true;
  }

  // The curved primitives of fewer parameters than curved fitted to its members by least
  // squares: a sphere (started from Kasa's algebraic fit) for a cylinder or a cone, a cylinder
  // on the cone's axis for a cone. The plausible ones.
  std::vector<Primitive> simplerCurved(const Primitive& curved, const std::vector<int>& members) const
  {
    std::vector<Primitive> simpler;
    if (P.spheres && parameterCount(PrimitiveType::Sphere) < parameterCount(curved.type))
    {
      simpler.push_back(fitLeastSquares(algebraicSphere(Points, members), Points, members));
    }
    if (P.cylinders && curved.type == PrimitiveType::Cone)
    {
      Primitive cylinder;
      cylinder.type = PrimitiveType::Cylinder;
      cylinder.axis = curved.axis;
      cylinder.center = curved.center;
      for (int i : members)
      {
        const Vec3 v = Points[i] - curved.center;
        cylinder.radius += (v - v.dot(curved.axis) * curved.axis).norm() / static_cast<double>(members.size());
      }
      simpler.push_back(fitLeastSquares(cylinder, Points, members));
    }
    simpler.erase(std::remove_if(simpler.begin(), simpler.end(), [&](const Primitive& s) { return !plausible(s); }), simpler.end());
    return simpler;
  }

  bool extract(const Candidate& candidate, DetectedPrimitive& primitive, std::vector<int>& component) const
  {
    ForwardSearchResult refined;
    if (!grow(candidate.shape, component, refined))
    {
      return false;
    }
    // the simplest primitive that explains the members takes the candidate's place, and so on
    // (parameters only decrease): the plane that explains them as well (planeExplains), on the
    // component, or a curved primitive of fewer parameters that fits their observations closer,
    // which grows anew (a cone drawn on a noisy band of a sphere, when the faces' normals scatter
    // beyond the normal threshold: the sphere grows over the whole surface). Fewer parameters
    // and a closer fit make the better model by any criterion. Squared sums below leastSquaredSum
    // tell no fit from another (the vertices of a band of faces around an axis, one face high,
    // lie on two circles, through which a sphere passes as exactly as the cone or the cylinder
    // does), and there the candidate, drawn and grown with its normals, stays.
    bool simplified = true;
    while (simplified && refined.shape.type != PrimitiveType::Plane)
    {
      simplified = false;
      if (P.planes && planeExplains(refined.shape, refined.members))
      {
        Primitive plane;
        plane.type = PrimitiveType::Plane;
        refined = forwardSearch(fitLeastSquares(plane, Points, refined.members), Points, Normals, component, Refinement);
        simplified = true;
      }
      else if (static_cast<int>(refined.members.size()) >= P.minimumSupport)
      {
        const std::vector<int> observed = observations(refined.members);
        const double least = leastSquaredSum(static_cast<double>(observed.size()));
        const double sum = std::max(least, fitSquaredSum(refined.shape, observed));
        for (const Primitive& simpler : simplerCurved(refined.shape, refined.members))
        {
          ForwardSearchResult regrown;
          std::vector<int> regrownComponent;
          if (std::max(least, fitSquaredSum(simpler, observed)) < sum && grow(simpler, regrownComponent, regrown))
          {
            refined = std::move(regrown);
            component = std::move(regrownComponent);
            simplified = true;
            break;
          }
        }
      }
    }
    if (static_cast<int>(refined.members.size()) < P.minimumSupport || !plausible(refined.shape))
    {
      return false;
    }
    primitive.shape = refined.shape;
    primitive.members = refined.members;
    primitive.rmsDistance = refined.rmsDistance;
    primitive.maxDistance = refined.maxDistance;
    return true;
  }

  // The largest normal deviation a primitive admits: the forward search's outlier rule (ForwardSearch.h)
  // on its members' normal deviations, jump x their RMS angle, at least the normal threshold and
  // at most 90 degrees. Faces a few times wider than the vertex noise tilt by about noise / width
  // radians, beyond any fixed threshold for some of them (about 10% beyond 20 degrees at 5x).
  double admissionAngle(const DetectedPrimitive& primitive) const
  {
    double squared = 0;
    for (int i : primitive.members)
    {
      const double cosine = std::abs(Normals[i].dot(primitive.shape.normalAt(Points[i])));
      squared += std::pow(std::acos(std::min(1.0, cosine)), 2);
    }
    const double rms = std::sqrt(squared / static_cast<double>(primitive.members.size()));
    return std::clamp(Refinement.jump * rms, P.normalThreshold, M_PI / 2);
  }

  // The RMS distance of the vertices of a primitive's faces from its surface: the vertex noise
  // (its component along the normal), and for an exact mesh of a curved surface the offset of the
  // fit to the face barycenters.
  double vertexNoise(const DetectedPrimitive& primitive) const
  {
    double squared = 0;
    long count = 0;
    for (int i : primitive.members)
    {
      for (int v : Mesh->faces[i])
      {
        squared += std::pow(primitive.shape.distance(Mesh->vertices[v]), 2);
        ++count;
      }
    }
    return count > 0 ? std::sqrt(squared / static_cast<double>(count)) : 0;
  }

  // The samples a primitive explains (Schnabel et al.'s refitting: the compatible samples of the
  // final fit, gathered again): its members and the samples within its admission distance
  // (ForwardSearch.h) and admission angle, in the connected components of its members. Increasing.
  // A face whose vertices all lie within the admission distance of the vertex noise (the forward
  // search's outlier rule on vertexNoise) lies on the surface as far as the noise tells, whatever
  // its normal: a face not much wider than the noise (a fan's thin triangle at a pole or an apex)
  // has the noise's normal, up to 90 degrees off; the normal of a face of a neighbouring surface
  // deviates as much, but its vertices away from the common edge lie off the surface by their
  // distance from the edge times the sine of the angle between the surfaces.
  std::vector<int> explained(const DetectedPrimitive& primitive) const
  {
    const Primitive& shape = primitive.shape;
    const double reach = admissionDistance(Refinement, primitive.rmsDistance);
    const double cosAngle = std::cos(admissionAngle(primitive));
    const double vertexReach = Mesh ? admissionDistance(Refinement, vertexNoise(primitive)) : 0;
    auto verticesNear = [&](int i) {
      return Mesh && std::all_of(Mesh->faces[i].begin(), Mesh->faces[i].end(),
                       [&](int v) { return shape.distance(Mesh->vertices[v]) <= vertexReach; });
    };
    const long n = static_cast<long>(Valid.size());
    std::vector<char> flag(n);
#pragma omp parallel for schedule(static) if (n >= ParallelSamples)
    for (long a = 0; a < n; ++a)
    {
      const int i = Valid[a];
      Vec3 normal;
      flag[a] = shape.distance(Points[i], normal) <= reach && (std::abs(Normals[i].dot(normal)) >= cosAngle || verticesNear(i));
    }
    std::vector<int> admitted;
    for (long a = 0; a < n; ++a)
    {
      if (flag[a])
      {
        admitted.push_back(Valid[a]);
      }
    }
    // the admitted samples beyond its members that are connected to them (connectedLeft)
    std::vector<int> outside, joining, samples;
    std::set_difference(admitted.begin(), admitted.end(), primitive.members.begin(), primitive.members.end(), std::back_inserter(outside));
    for (long b : connectedLeft(primitive, outside, [](int) { return true; }))
    {
      joining.push_back(outside[b]);
    }
    std::set_union(joining.begin(), joining.end(), primitive.members.begin(), primitive.members.end(), std::back_inserter(samples));
    return samples;
  }

  // After the greedy extraction, which never revisits a primitive (Schnabel et al. section 4.2):
  //   1. a primitive of whose members the other primitives explain all but fewer than the
  //      minimum support is redundant (a piece of a surface that noise split off, a cone tangent
  //      to two flat faces found before them) and goes, the smallest first;
  //   2. a sample no kept primitive holds goes to the kept primitive that explains it with the
  //      least distance relative to its admission distance (noisy faces beyond the normal
  //      threshold, the members of a redundant primitive);
  //   3. a primitive that gained samples is fit again to its members by least squares;
  //   4. a sample still in none joins the primitive it is compatible with (joinCompatible).
  void settle(std::vector<DetectedPrimitive>& found) const
  {
    const int count = static_cast<int>(found.size());
    std::vector<std::vector<int>> explains(count);
    std::vector<int> explainers(Points.size(), 0); // kept primitives that explain a sample
    for (int p = 0; p < count; ++p)
    {
      explains[p] = explained(found[p]);
      for (int i : explains[p])
      {
        ++explainers[i];
      }
    }
    std::vector<int> bySize(count);
    std::iota(bySize.begin(), bySize.end(), 0);
    std::stable_sort(bySize.begin(), bySize.end(), [&](int a, int b) { return found[a].members.size() < found[b].members.size(); });
    std::vector<char> kept(count, 1), own(Points.size(), 0);
    for (int p : bySize)
    {
      for (int i : explains[p])
      {
        own[i] = 1;
      }
      int unexplained = 0;
      for (int i : found[p].members)
      {
        unexplained += explainers[i] - own[i] == 0;
      }
      for (int i : explains[p])
      {
        own[i] = 0;
      }
      if (unexplained < P.minimumSupport)
      {
        kept[p] = 0;
        for (int i : explains[p])
        {
          --explainers[i];
        }
      }
    }
    std::vector<int> owner(Points.size(), -1);
    std::vector<double> closeness(Points.size(), std::numeric_limits<double>::infinity());
    for (int p = 0; p < count; ++p)
    {
      if (!kept[p])
      {
        continue;
      }
      for (int i : found[p].members)
      {
        owner[i] = p;
        closeness[i] = -1; // held: stays
      }
    }
    for (int p = 0; p < count; ++p)
    {
      if (!kept[p])
      {
        continue;
      }
      const double reach = admissionDistance(Refinement, found[p].rmsDistance);
      for (int i : explains[p])
      {
        const double relative = found[p].shape.distance(Points[i]) / reach;
        if (relative < closeness[i])
        {
          closeness[i] = relative;
          owner[i] = p;
        }
      }
    }
    std::vector<std::vector<int>> members(count);
    for (int i : Valid)
    {
      if (owner[i] >= 0)
      {
        members[owner[i]].push_back(i);
      }
    }
    std::vector<DetectedPrimitive> settled;
    for (int p = 0; p < count; ++p)
    {
      if (!kept[p])
      {
        continue;
      }
      DetectedPrimitive primitive = std::move(found[p]);
      if (members[p].size() > primitive.members.size())
      {
        const Primitive refit = fitLeastSquares(primitive.shape, Points, members[p]);
        if (plausible(refit))
        {
          primitive.shape = refit;
        }
        primitive.members = std::move(members[p]);
        const DistanceStatistics statistics = distanceStatistics(primitive.shape, Points, primitive.members);
        primitive.rmsDistance = statistics.rms;
        primitive.maxDistance = statistics.max;
      }
      settled.push_back(std::move(primitive));
    }
    found = std::move(settled);
    joinCompatible(found);
  }

  // The positions b in left of the samples that pass near and lie in a connected component of
  // the primitive's members (components), increasing.
  template <typename Near>
  std::vector<long> connectedLeft(const DetectedPrimitive& primitive, const std::vector<int>& left, Near near) const
  {
    // the primitive's members and the samples left that pass, increasing; b >= 0: left[b]
    const std::vector<int>& members = primitive.members;
    std::vector<int> samples;
    std::vector<long> leftIndex;
    std::size_t m = 0;
    for (std::size_t b = 0; b < left.size(); ++b)
    {
      const int i = left[b];
      if (!near(i))
      {
        continue;
      }
      for (; m < members.size() && members[m] < i; ++m)
      {
        samples.push_back(members[m]);
        leftIndex.push_back(-1);
      }
      samples.push_back(i);
      leftIndex.push_back(static_cast<long>(b));
    }
    if (std::none_of(leftIndex.begin(), leftIndex.end(), [](long b) { return b >= 0; }))
    {
      return {};
    }
    for (; m < members.size(); ++m)
    {
      samples.push_back(members[m]);
      leftIndex.push_back(-1);
    }
    const std::vector<long> component = components(Points, samples, P.clusterEpsilon, faces(), VertexOwner);
    std::vector<char> reached(samples.size(), 0);
    for (std::size_t a = 0; a < samples.size(); ++a)
    {
      if (leftIndex[a] < 0)
      {
        reached[component[a]] = 1;
      }
    }
    std::vector<long> connected;
    for (std::size_t a = 0; a < samples.size(); ++a)
    {
      if (leftIndex[a] >= 0 && reached[component[a]])
      {
        connected.push_back(leftIndex[a]);
      }
    }
    return connected;
  }

  // Samples left just beyond epsilon of a primitive (up to EndsWidth epsilon, their normals
  // within the threshold, connected to its members) are often the ends of its surface that the
  // least-squares fit leaves out: the ends of a fandisk blend lie 1.03-1.24 epsilon from the
  // cylinder fit to the rest. The minimax fit (fitMinimax) to the members and those samples takes
  // the primitive's place when more of them all are compatible with it. True when it did.
  bool fitMinimaxWithEnds(DetectedPrimitive& primitive, const std::vector<int>& left) const
  {
    const Primitive& shape = primitive.shape;
    // a face that leaves the surface is no end of it: a chamfer face of the joint lies 0.93
    // epsilon from a cylinder at its barycenter and 8.5 epsilon at its far vertex
    auto faceNear = [&](int i) {
      return !Mesh || std::all_of(Mesh->faces[i].begin(), Mesh->faces[i].end(),
                        [&](int v) { return shape.distance(Mesh->vertices[v]) < EndsWidth * P.epsilon; });
    };
    bool beyond = false; // some sample of the band lies beyond epsilon
    const std::vector<long> band = connectedLeft(primitive, left, [&](int i) {
      Vec3 normal;
      const double distance = shape.distance(Points[i], normal);
      const bool near = distance < EndsWidth * P.epsilon && std::abs(Normals[i].dot(normal)) >= CosAlpha && faceNear(i);
      beyond = beyond || (near && distance >= P.epsilon);
      return near;
    });
    if (band.empty() || !beyond)
    {
      return false;
    }
    std::vector<int> samples = primitive.members;
    for (long b : band)
    {
      samples.push_back(left[b]);
    }
    auto compatibleCount = [&](const Primitive& s) {
      return std::count_if(samples.begin(), samples.end(), [&](int i) { return s.compatible(Points[i], Normals[i], P.epsilon, CosAlpha); });
    };
    const Primitive minimax = fitMinimax(shape, Points, samples, P.epsilon);
    if (plausible(minimax) && compatibleCount(minimax) > compatibleCount(shape))
    {
      primitive.shape = minimax;
      const DistanceStatistics statistics = distanceStatistics(primitive.shape, Points, primitive.members);
      primitive.rmsDistance = statistics.rms;
      primitive.maxDistance = statistics.max;
      return true;
    }
    return false;
  }

public:
  /// Once the search is over: each primitive whose fit leaves the ends of its surface just
  /// beyond epsilon takes the minimax fit that holds them (fitMinimaxWithEnds), and the samples
  /// left join the primitives they are compatible with then (joinCompatible).
  void holdEnds(std::vector<DetectedPrimitive>& found) const
  {
    const std::vector<int> left = unheld(found);
    bool refit = false;
    for (DetectedPrimitive& primitive : found)
    {
      refit = fitMinimaxWithEnds(primitive, left) || refit;
    }
    if (refit)
    {
      joinCompatible(found);
    }
  }

private:

  // A sample in no primitive joins one it is compatible with (Schnabel et al. section 4.4:
  // within epsilon, its normal within the threshold) in a connected component of its members,
  // the nearest if several: the faces of a blend or of a coarse tessellation beside an exact
  // primitive, which the forward search left out as farther than its floor. The primitive's
  // shape stays the fit to the samples it explains; its distance statistics count them all.
  void joinCompatible(std::vector<DetectedPrimitive>& found) const
  {
    const std::vector<int> left = unheld(found);
    std::vector<int> owner(left.size(), -1);
    std::vector<double> nearest(left.size(), std::numeric_limits<double>::infinity());
    std::vector<char> gained(found.size(), 0);
    for (std::size_t p = 0; p < found.size() && !left.empty(); ++p)
    {
      const DetectedPrimitive& primitive = found[p];
      const std::vector<long> joining = connectedLeft(primitive, left,
        [&](int i) { return primitive.shape.compatible(Points[i], Normals[i], P.epsilon, CosAlpha); });
      for (long b : joining)
      {
        const double distance = primitive.shape.distance(Points[left[b]]);
        if (distance < nearest[b])
        {
          nearest[b] = distance;
          owner[b] = static_cast<int>(p);
        }
      }
    }
    for (std::size_t b = 0; b < left.size(); ++b)
    {
      if (owner[b] >= 0)
      {
        found[owner[b]].members.push_back(left[b]);
        gained[owner[b]] = 1;
      }
    }
    for (std::size_t p = 0; p < found.size(); ++p)
    {
      if (gained[p])
      {
        DetectedPrimitive& primitive = found[p];
        std::sort(primitive.members.begin(), primitive.members.end());
        const DistanceStatistics statistics = distanceStatistics(primitive.shape, Points, primitive.members);
        primitive.rmsDistance = statistics.rms;
        primitive.maxDistance = statistics.max;
      }
    }
  }

  void removeMembers(const std::vector<int>& members)
  {
    for (int i : members)
    {
      Available[i] = 0;
    }
    Remaining.erase(std::remove_if(Remaining.begin(), Remaining.end(), [&](int i) { return !Available[i]; }), Remaining.end());
    // the subsets keep their available samples, in their order
    long kept = 0;
    for (std::size_t k = 0, a = 0; k < SubsetEnd.size(); ++k)
    {
      for (; a < static_cast<std::size_t>(SubsetEnd[k]); ++a)
      {
        if (Available[Order[a]])
        {
          Order[kept] = Order[a];
          OrderPoints[kept] = OrderPoints[a];
          OrderNormals[kept] = OrderNormals[a];
          ++kept;
        }
      }
      SubsetEnd[k] = kept;
    }
    Order.resize(kept);
    OrderPoints.resize(kept);
    OrderNormals.resize(kept);
    // candidates drawn from removed samples go; the others lose the removed hits (Schnabel et
    // al. section 4.5: the scores are kept up to date, not evaluated again)
    Candidates.erase(std::remove_if(Candidates.begin(), Candidates.end(),
                       [&](const Candidate& c) { return !Available[c.samples[0]] || !Available[c.samples[1]] || !Available[c.samples[2]]; }),
      Candidates.end());
    for (Candidate& c : Candidates)
    {
      c.hits.erase(std::remove_if(c.hits.begin(), c.hits.end(), [&](int i) { return !Available[i]; }), c.hits.end());
      estimate(c);
    }
  }

  const PointList& Points;
  const std::vector<Vec3>& Normals;
  const SampleFaces* Mesh; // or none
  mutable std::vector<int> VertexOwner; // scratch of largestComponent: a sample per vertex, -1
  RansacParameters P;
  double CosAlpha;
  double Diagonal = 0;
  ForwardSearchSettings Refinement; // of every extracted primitive
  MortonOctree Octree;
  std::vector<int> Valid; // the samples with a unit normal, increasing
  std::vector<char> Available;
  std::vector<int> Remaining; // the available samples, increasing
  std::vector<int> Order;      // the available samples in random order: the scoring subsets are ranges of it
  std::vector<long> SubsetEnd; // the end of each subset in Order
  PointList OrderPoints;       // the positions and normals of the samples in Order, in its order:
  std::vector<Vec3> OrderNormals; // a subset is scored from contiguous memory
  std::vector<Candidate> Candidates;
  std::vector<PrimitiveType> Types;
  int Levels = 1;
  std::vector<double> LevelDraws, LevelScore;
  long Draws = 0;
  std::mt19937_64 Random;
};
}

std::vector<DetectedPrimitive> detectPrimitives(const PointList& points, const std::vector<Vec3>& normals,
  const RansacParameters& parameters, const SampleFaces* faces, const Progress& progress)
{
  if (points.size() != normals.size() || (faces && faces->faces.size() != points.size()))
  {
    throw InvalidInputException("primitive detection: one normal (and face, if faces are given) per sample is needed");
  }
  if (faces)
  {
    for (const std::vector<int>& face : faces->faces)
    {
      for (int v : face)
      {
        if (v < 0 || v >= static_cast<int>(faces->vertices.size()))
        {
          throw InvalidInputException("primitive detection: a face has a vertex index out of range");
        }
      }
    }
    requireFinite(faces->vertices, "primitive detection face vertices");
  }
  requireFinite(points, "primitive detection samples");
  if (!(parameters.epsilon > 0) || !(parameters.clusterEpsilon > 0) || !(parameters.normalThreshold > 0) ||
    !(parameters.normalThreshold <= M_PI / 2) || parameters.minimumSupport < 3 || !(parameters.probability > 0) ||
    !(parameters.probability < 1))
  {
    throw InvalidInputException("primitive detection: epsilon and cluster epsilon must be positive, the normal threshold in "
                                "(0, 90] degrees, the minimum support at least 3 and the probability in (0, 1)");
  }
  std::vector<int> valid;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (normals[i].allFinite() && std::abs(normals[i].norm() - 1) < 1e-6)
    {
      valid.push_back(static_cast<int>(i));
    }
  }
  if (valid.empty())
  {
    return {};
  }
  Search search(points, normals, faces, parameters, valid);
  std::vector<DetectedPrimitive> found = search.run(progress);
  search.holdEnds(found);
  return found;
}
} // namespace mlsdeform

