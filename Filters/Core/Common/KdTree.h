// A static kd-tree over 3D points: nearest neighbours and, given one radius per point, "which
// balls contain x" (the MLS supports covering a position) and searches shared by nearby positions.
#pragma once

#include "Common/CoreTypes.h"

#include <functional>

namespace mlsdeform
{
class KdTree
{
public:
  KdTree() = default;
  explicit KdTree(const PointList& points) { build(points); }
  void build(const PointList& points);

  /// Gives each point a ball radius; enables containing().
  void setRadii(const std::vector<double>& radii);

  /// Index of the nearest point (-1 if the tree is empty). A hint (a point likely near x, such as
  /// the answer for a nearby x) bounds the search from the start; of points as near as the hint,
  /// the hint is returned.
  int nearest(const Vec3& x, int hint = -1) const;
  /// Up to k nearest points, closest first, with squared distances.
  void kNearest(const Vec3& x, int k, std::vector<int>& indices, std::vector<double>& squaredDistances) const;
  /// For positions in the box [lower, upper] sharing one search (requires setRadii): the balls i
  /// that may be among the k of least |p_i - x| / radius_i for some x of the box, in increasing
  /// order. Those of radius 0 are never taken.
  void leastRelativeCandidates(const Vec3& lower, const Vec3& upper, int k, std::vector<int>& candidates) const;
  /// Up to k of the candidates with the smallest |p_i - x| / radius_i, smallest first (ties by
  /// index), with those ratios squared: the balls that must grow least, relative to their radius,
  /// to contain x. With the candidates of a box holding x, the k least of all balls.
  void kLeastRelative(const Vec3& x, int k, const std::vector<int>& candidates, std::vector<int>& indices,
    std::vector<double>& squaredRatios) const;
  /// All points i with |p_i - x| < radius_i (requires setRadii), in increasing order.
  void containing(const Vec3& x, std::vector<int>& indices) const;
  /// Whether at least count of the candidates (meetingBox of a box holding x) contain x.
  bool containedInAtLeast(const Vec3& x, int count, const std::vector<int>& candidates) const;
  /// All balls i that may contain a point of the box [lower, upper], in increasing order (requires
  /// setRadii): a superset of containing(x) for every x in the box, so that nearby positions share
  /// one search and each filters the list with the exact test |p_i - x| < radius_i.
  void meetingBox(const Vec3& lower, const Vec3& upper, std::vector<int>& indices) const;
  /// meetingBox among candidates (increasing), such as those of a larger box: the same test, the
  /// same order.
  void meetingBoxAmong(const Vec3& lower, const Vec3& upper, const std::vector<int>& candidates, std::vector<int>& indices) const;
  /// The ball (requires setRadii) holding the object nearest to x, where squaredDistance(i) is the
  /// squared distance from x to the object inside ball i (a triangle inside the ball around its
  /// centroid): visits only the nodes whose balls come nearer than the best so far. -1 if empty.
  int nearestObject(const Vec3& x, const std::function<double(int)>& squaredDistance) const;

  std::size_t size() const { return Points.size(); }

private:
  struct Node
  {
    Vec3 lower, upper;   // bounding box of the node's points
    Vec3 reachLower = Vec3::Zero(), reachUpper = Vec3::Zero(); // bounding box of the node's balls (with setRadii)
    double maxRadius = 0; // largest ball radius below this node
    int begin = 0, end = 0; // range in Order, Points and Radii
    int left = -1, right = -1;
  };
  int buildNode(const PointList& points, int begin, int end);
  /// The balls (input numbers, increasing) of the nodes with nodeMeets(node) whose
  /// ballMeets(position in Order) holds (requires setRadii).
  template <typename NodeMeets, typename BallMeets>
  void collectBalls(NodeMeets nodeMeets, BallMeets ballMeets, std::vector<int>& indices) const;
  void setReach(int node);
  /// The k points of least key(position in Order), visiting only nodes whose bound(node) is below the
  /// k-th least key found so far; sorted by key.
  template <typename PointKey, typename NodeBound>
  void kSmallest(int k, PointKey key, NodeBound bound, std::vector<int>& indices, std::vector<double>& keys) const;
  static double squaredDistanceToBox(const Node& node, const Vec3& x)
  {
    const Vec3 d = (node.lower - x).cwiseMax(x - node.upper).cwiseMax(0.0);
    return d.squaredNorm();
  }


  // In tree order: the i-th point (and ball radius) is the input's Order[i], so that a leaf's
  // points are contiguous in memory.
  PointList Points;
  std::vector<int> Order;
  std::vector<int> Position; // inverse of Order
  std::vector<Node> Nodes;
  std::vector<double> Radii;
};
} // namespace mlsdeform
