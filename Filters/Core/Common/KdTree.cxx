#include "Common/KdTree.h"

#include <algorithm>
#include <limits>

namespace mlsdeform
{
namespace
{
// Points per leaf at most. The searches of a set-up (the supports' cover, Phi's supports, the
// blend's 9 nearest sites) visit fewer nodes with larger leaves, whose points are contiguous: on
// the 400k-point hull case the sampling took 0.63 s with 32 against 0.67 s with 8 and 16, and the
// set-up 2.86 s against 3.01 s (8) and 2.94 s (16), medians of 5-9 runs; 64 was slower again.
constexpr int LeafSize = 32;

// Depth-first traversal stack without heap allocation: a balanced tree over fewer than 2^60
// points is shallower than 60 levels and holds at most one pending sibling per level.
struct TraversalStack
{
  int items[128];
  int count = 0;
  void push_back(int i) { items[count++] = i; }
  int back() const { return items[count - 1]; }
  void pop_back() { --count; }
  bool empty() const { return count == 0; }
};

// The squared distance between the boxes [lower, upper] and [a, b] (a point: a = b).
double squaredDistanceBetweenBoxes(const Vec3& lower, const Vec3& upper, const Vec3& a, const Vec3& b)
{
  return (lower - b).cwiseMax(a - upper).cwiseMax(0.0).squaredNorm();
}

// A ball containing x of a box is nearer the box than its radius: |p - box| <= |p - x| < r
// (rounding is monotonic). The margin keeps that true whatever order the sums are taken in.
constexpr double BoxMargin = 1 + 1e-9;

// A ball's squared distance over its squared radius (infinite for radius 0: never taken).
double squaredRatio(double squaredDistance, double radius)
{
  return radius > 0 ? squaredDistance / (radius * radius) : std::numeric_limits<double>::infinity();
}

// The k least keys seen so far with their indices, sorted (k is small: insertion beats a heap);
// of equal keys the first seen stays first. Works in the caller's vectors, sized k while it runs
// (shifted in place: vector insertions took a third of a 9-nearest search), trimmed by finish().
class SmallestK
{
public:
  SmallestK(int k, std::vector<int>& indices, std::vector<double>& keys)
    : K(std::max(k, 0))
    , Indices(indices)
    , Keys(keys)
  {
    Indices.resize(K);
    Keys.resize(K);
  }
  double worst() const
  {
    return Count < K ? std::numeric_limits<double>::infinity() : K > 0 ? Keys[Count - 1] : -std::numeric_limits<double>::infinity();
  }
  void insert(double key, int index)
  {
    if (!(key < worst()))
    {
      return;
    }
    int at = Count < K ? Count++ : K - 1;
    for (; at > 0 && Keys[at - 1] > key; --at)
    {
      Keys[at] = Keys[at - 1];
      Indices[at] = Indices[at - 1];
    }
    Keys[at] = key;
    Indices[at] = index;
  }
  void finish()
  {
    Indices.resize(Count);
    Keys.resize(Count);
  }

private:
  int K;
  int Count = 0;
  std::vector<int>& Indices;
  std::vector<double>& Keys;
};

// Pushes both children, the one of smaller bound (nearer) last so that it is visited first.
template <typename Node, typename Nodes, typename Bound>
void pushChildrenOf(const Node& node, const Nodes& nodes, TraversalStack& stack, Bound bound)
{
  if (bound(nodes[node.left]) < bound(nodes[node.right]))
  {
    stack.push_back(node.right);
    stack.push_back(node.left);
  }
  else
  {
    stack.push_back(node.left);
    stack.push_back(node.right);
  }
}
}

void KdTree::build(const PointList& points)
{
  Order.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    Order[i] = static_cast<int>(i);
  }
  Nodes.clear();
  Radii.clear();
  if (!points.empty())
  {
    Nodes.reserve(2 * points.size() / LeafSize + 2);
    buildNode(points, 0, static_cast<int>(points.size()));
  }
  Points.resize(points.size());
  Position.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    Points[i] = points[Order[i]];
    Position[Order[i]] = static_cast<int>(i);
  }
}

int KdTree::buildNode(const PointList& points, int begin, int end)
{
  Node node;
  node.begin = begin;
  node.end = end;
  node.lower = node.upper = points[Order[begin]];
  for (int i = begin + 1; i < end; ++i)
  {
    node.lower = node.lower.cwiseMin(points[Order[i]]);
    node.upper = node.upper.cwiseMax(points[Order[i]]);
  }
  const int index = static_cast<int>(Nodes.size());
  Nodes.push_back(node);
  if (end - begin > LeafSize)
  {
    int axis;
    (node.upper - node.lower).maxCoeff(&axis);
    const int middle = (begin + end) / 2;
    std::nth_element(Order.begin() + begin, Order.begin() + middle, Order.begin() + end,
      [&](int a, int b) { return points[a][axis] < points[b][axis]; });
    const int left = buildNode(points, begin, middle);
    const int right = buildNode(points, middle, end);
    Nodes[index].left = left;
    Nodes[index].right = right;
  }
  return index;
}

void KdTree::setRadii(const std::vector<double>& radii)
{
  Radii.resize(radii.size());
  for (std::size_t i = 0; i < radii.size() && i < Order.size(); ++i)
  {
    Radii[i] = radii[Order[i]];
  }
  if (!Nodes.empty() && Radii.size() == Points.size())
  {
    setReach(0);
  }
}

void KdTree::setReach(int index)
{
  Node& node = Nodes[index];
  if (node.left < 0)
  {
    node.maxRadius = 0;
    node.reachLower = node.reachUpper = Points[node.begin];
    for (int i = node.begin; i < node.end; ++i)
    {
      node.maxRadius = std::max(node.maxRadius, Radii[i]);
      const Vec3 reach = Vec3::Constant(Radii[i]);
      node.reachLower = node.reachLower.cwiseMin(Points[i] - reach);
      node.reachUpper = node.reachUpper.cwiseMax(Points[i] + reach);
    }
    return;
  }
  setReach(node.left);
  setReach(node.right);
  const Node& left = Nodes[node.left];
  const Node& right = Nodes[node.right];
  node.maxRadius = std::max(left.maxRadius, right.maxRadius);
  node.reachLower = left.reachLower.cwiseMin(right.reachLower);
  node.reachUpper = left.reachUpper.cwiseMax(right.reachUpper);
}

int KdTree::nearest(const Vec3& x, int hint) const
{
  int best = hint;
  double bestDistance = hint >= 0 ? (Points[Position[hint]] - x).squaredNorm() : std::numeric_limits<double>::infinity();
  TraversalStack stack;
  if (!Nodes.empty())
  {
    stack.push_back(0);
  }
  while (!stack.empty())
  {
    const Node& node = Nodes[stack.back()];
    stack.pop_back();
    if (squaredDistanceToBox(node, x) >= bestDistance)
    {
      continue;
    }
    if (node.left < 0)
    {
      for (int i = node.begin; i < node.end; ++i)
      {
        const double d2 = (Points[i] - x).squaredNorm();
        if (d2 < bestDistance)
        {
          bestDistance = d2;
          best = Order[i];
        }
      }
    }
    else
    {
      pushChildrenOf(node, Nodes, stack, [&](const Node& child) { return squaredDistanceToBox(child, x); });
    }
  }
  return best;
}

void KdTree::kNearest(const Vec3& x, int k, std::vector<int>& indices, std::vector<double>& squaredDistances) const
{
  kSmallest(
    k, [&](int i) { return (Points[i] - x).squaredNorm(); }, [&](const Node& node) { return squaredDistanceToBox(node, x); },
    indices, squaredDistances);
}

int KdTree::nearestObject(const Vec3& x, const std::function<double(int)>& squaredDistance) const
{
  std::vector<int> indices;
  std::vector<double> keys;
  kSmallest(
    1, [&](int i) { return squaredDistance(Order[i]); },
    [&](const Node& node) { return (node.reachLower - x).cwiseMax(x - node.reachUpper).cwiseMax(0.0).squaredNorm(); }, indices, keys);
  return indices.empty() ? -1 : indices.front();
}

void KdTree::leastRelativeCandidates(const Vec3& lower, const Vec3& upper, int k, std::vector<int>& candidates) const
{
  candidates.clear();
  if (Nodes.empty() || Radii.size() != Points.size() || k <= 0)
  {
    return;
  }
  // Every x of the box has k balls with ratio at most U, the k-th least ratio of the box's farthest
  // point; a ball nearer to the box than U times its radius may be among x's k least, no other.
  const auto nearest = [&](const Vec3& a, const Vec3& b) { return squaredDistanceBetweenBoxes(lower, upper, a, b); };
  const auto nodeBound = [&](const Node& node) { return squaredRatio(nearest(node.lower, node.upper), node.maxRadius); };
  std::vector<int> indices;
  std::vector<double> farthest;
  kSmallest(
    k,
    [&](int i) {
      return squaredRatio((Points[i] - lower).cwiseAbs().cwiseMax((Points[i] - upper).cwiseAbs()).squaredNorm(), Radii[i]);
    },
    nodeBound, indices, farthest);
  constexpr double Margin = 1 + 1e-9; // for the roundings of the bounds
  const double bound = static_cast<int>(farthest.size()) < k ? std::numeric_limits<double>::infinity() : farthest.back() * Margin;
  collectBalls([&](const Node& node) { return nodeBound(node) <= bound; },
    [&](int i) { return Radii[i] > 0 && squaredRatio(nearest(Points[i], Points[i]), Radii[i]) <= bound; }, candidates);
}

void KdTree::kLeastRelative(const Vec3& x, int k, const std::vector<int>& candidates, std::vector<int>& indices,
  std::vector<double>& squaredRatios) const
{
  indices.clear();
  squaredRatios.clear();
  if (Radii.size() != Points.size())
  {
    return;
  }
  SmallestK smallest(k, indices, squaredRatios);
  for (int j : candidates)
  {
    smallest.insert(squaredRatio((Points[Position[j]] - x).squaredNorm(), Radii[Position[j]]), j);
  }
  smallest.finish();
}

template <typename PointKey, typename NodeBound>
void KdTree::kSmallest(int k, PointKey key, NodeBound bound, std::vector<int>& indices, std::vector<double>& keys) const
{
  indices.clear();
  keys.clear();
  if (Nodes.empty() || k <= 0)
  {
    return;
  }
  SmallestK smallest(k, indices, keys);
  TraversalStack stack;
  stack.push_back(0);
  while (!stack.empty())
  {
    const Node& node = Nodes[stack.back()];
    stack.pop_back();
    if (bound(node) >= smallest.worst())
    {
      continue;
    }
    if (node.left < 0)
    {
      for (int i = node.begin; i < node.end; ++i)
      {
        smallest.insert(key(i), Order[i]);
      }
    }
    else
    {
      pushChildrenOf(node, Nodes, stack, bound);
    }
  }
  smallest.finish();
}

void KdTree::containing(const Vec3& x, std::vector<int>& indices) const
{
  collectBalls(
    [&](const Node& node) {
      return !(x.array() < node.reachLower.array()).any() && !(x.array() > node.reachUpper.array()).any() &&
        squaredDistanceToBox(node, x) < node.maxRadius * node.maxRadius;
    },
    [&](int i) { return (Points[i] - x).squaredNorm() < Radii[i] * Radii[i]; }, indices);
}

bool KdTree::containedInAtLeast(const Vec3& x, int count, const std::vector<int>& candidates) const
{
  int found = 0;
  for (std::size_t a = 0; a < candidates.size() && found < count; ++a)
  {
    const int i = Position[candidates[a]];
    found += (Points[i] - x).squaredNorm() < Radii[i] * Radii[i]; // the test of containing
  }
  return found >= count;
}

void KdTree::meetingBox(const Vec3& lower, const Vec3& upper, std::vector<int>& indices) const
{
  collectBalls(
    [&](const Node& node) {
      return !(upper.array() < node.reachLower.array()).any() && !(lower.array() > node.reachUpper.array()).any() &&
        squaredDistanceBetweenBoxes(lower, upper, node.lower, node.upper) < node.maxRadius * node.maxRadius * BoxMargin;
    },
    [&](int i) { return squaredDistanceBetweenBoxes(lower, upper, Points[i], Points[i]) < Radii[i] * Radii[i] * BoxMargin; },
    indices);
}

void KdTree::meetingBoxAmong(const Vec3& lower, const Vec3& upper, const std::vector<int>& candidates, std::vector<int>& indices) const
{
  // every candidate written, the count advanced for those that meet the box (no branch to mispredict)
  indices.resize(candidates.size());
  std::size_t count = 0;
  for (int j : candidates)
  {
    const int i = Position[j];
    indices[count] = j;
    count += squaredDistanceBetweenBoxes(lower, upper, Points[i], Points[i]) < Radii[i] * Radii[i] * BoxMargin;
  }
  indices.resize(count);
}

template <typename NodeMeets, typename BallMeets>
void KdTree::collectBalls(NodeMeets nodeMeets, BallMeets ballMeets, std::vector<int>& indices) const
{
  indices.clear();
  if (Nodes.empty() || Radii.size() != Points.size())
  {
    return;
  }
  TraversalStack stack;
  stack.push_back(0);
  while (!stack.empty())
  {
    const Node& node = Nodes[stack.back()];
    stack.pop_back();
    if (!nodeMeets(node))
    {
      continue;
    }
    if (node.left < 0)
    {
      for (int i = node.begin; i < node.end; ++i)
      {
        if (ballMeets(i))
        {
          indices.push_back(Order[i]);
        }
      }
    }
    else
    {
      stack.push_back(node.left);
      stack.push_back(node.right);
    }
  }
  std::sort(indices.begin(), indices.end());
}
} // namespace mlsdeform
