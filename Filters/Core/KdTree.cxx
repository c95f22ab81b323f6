#include "KdTree.h"

#include <algorithm>
#include <limits>
#include <queue>

namespace mlsdeform
{
namespace
{
constexpr int LeafSize = 8;

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
}

void KdTree::build(const PointList& points)
{
  Points = points;
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
    buildNode(0, static_cast<int>(points.size()));
  }
}

int KdTree::buildNode(int begin, int end)
{
  Node node;
  node.begin = begin;
  node.end = end;
  node.lower = node.upper = Points[Order[begin]];
  for (int i = begin + 1; i < end; ++i)
  {
    node.lower = node.lower.cwiseMin(Points[Order[i]]);
    node.upper = node.upper.cwiseMax(Points[Order[i]]);
  }
  const int index = static_cast<int>(Nodes.size());
  Nodes.push_back(node);
  if (end - begin > LeafSize)
  {
    int axis;
    (node.upper - node.lower).maxCoeff(&axis);
    const int middle = (begin + end) / 2;
    std::nth_element(Order.begin() + begin, Order.begin() + middle, Order.begin() + end,
      [&](int a, int b) { return Points[a][axis] < Points[b][axis]; });
    const int left = buildNode(begin, middle);
    const int right = buildNode(middle, end);
    Nodes[index].left = left;
    Nodes[index].right = right;
  }
  return index;
}

void KdTree::setRadii(const std::vector<double>& radii)
{
  Radii = radii;
  if (!Nodes.empty())
  {
    maxRadiusBelow(0);
  }
}

double KdTree::maxRadiusBelow(int index)
{
  Node& node = Nodes[index];
  double r = 0;
  if (node.left < 0)
  {
    for (int i = node.begin; i < node.end; ++i)
    {
      r = std::max(r, Radii[Order[i]]);
    }
  }
  else
  {
    r = std::max(maxRadiusBelow(node.left), maxRadiusBelow(node.right));
  }
  Nodes[index].maxRadius = r;
  return r;
}

double KdTree::squaredDistanceToBox(const Node& node, const Vec3& x)
{
  const Vec3 d = (node.lower - x).cwiseMax(x - node.upper).cwiseMax(0.0);
  return d.squaredNorm();
}

int KdTree::nearest(const Vec3& x) const
{
  std::vector<int> indices;
  std::vector<double> distances;
  kNearest(x, 1, indices, distances);
  return indices.empty() ? -1 : indices[0];
}

void KdTree::kNearest(const Vec3& x, int k, std::vector<int>& indices, std::vector<double>& squaredDistances) const
{
  indices.clear();
  squaredDistances.clear();
  if (Nodes.empty() || k <= 0)
  {
    return;
  }
  // max-heap of the best k candidates so far
  std::priority_queue<std::pair<double, int>> best;
  auto bound = [&]() { return static_cast<int>(best.size()) < k ? std::numeric_limits<double>::infinity() : best.top().first; };
  TraversalStack stack;
  stack.push_back(0);
  while (!stack.empty())
  {
    const Node& node = Nodes[stack.back()];
    stack.pop_back();
    if (squaredDistanceToBox(node, x) >= bound())
    {
      continue;
    }
    if (node.left < 0)
    {
      for (int i = node.begin; i < node.end; ++i)
      {
        const double d2 = (Points[Order[i]] - x).squaredNorm();
        if (d2 < bound())
        {
          best.emplace(d2, Order[i]);
          if (static_cast<int>(best.size()) > k)
          {
            best.pop();
          }
        }
      }
    }
    else
    {
      // visit the nearer child first (pushed last)
      const double dl = squaredDistanceToBox(Nodes[node.left], x);
      const double dr = squaredDistanceToBox(Nodes[node.right], x);
      if (dl < dr)
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
  indices.resize(best.size());
  squaredDistances.resize(best.size());
  for (int i = static_cast<int>(best.size()) - 1; i >= 0; --i)
  {
    squaredDistances[i] = best.top().first;
    indices[i] = best.top().second;
    best.pop();
  }
}

void KdTree::withinRadius(const Vec3& x, double radius, std::vector<int>& indices) const
{
  indices.clear();
  if (Nodes.empty())
  {
    return;
  }
  const double r2 = radius * radius;
  TraversalStack stack;
  stack.push_back(0);
  while (!stack.empty())
  {
    const Node& node = Nodes[stack.back()];
    stack.pop_back();
    if (squaredDistanceToBox(node, x) >= r2)
    {
      continue;
    }
    if (node.left < 0)
    {
      for (int i = node.begin; i < node.end; ++i)
      {
        if ((Points[Order[i]] - x).squaredNorm() < r2)
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
}

void KdTree::containing(const Vec3& x, std::vector<int>& indices) const
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
    if (squaredDistanceToBox(node, x) >= node.maxRadius * node.maxRadius)
    {
      continue;
    }
    if (node.left < 0)
    {
      for (int i = node.begin; i < node.end; ++i)
      {
        const int j = Order[i];
        if ((Points[j] - x).squaredNorm() < Radii[j] * Radii[j])
        {
          indices.push_back(j);
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
