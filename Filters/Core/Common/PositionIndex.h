// Positions looked up by their exact coordinates (+0 = -0): a hash table of the distinct
// positions of a list, each numbered in order of first appearance.
#pragma once

#include "Common/CoreTypes.h"

#include <cstdint>

namespace mlsdeform
{
class PositionIndex
{
public:
  explicit PositionIndex(const PointList& positions);

  /// The number of the distinct position at x, or -1.
  long find(const Vec3& x) const;
  /// Per position of the list, the number of its distinct position.
  const std::vector<long>& numbers() const { return Numbers; }
  /// The distinct positions, in order of first appearance.
  const PointList& distinct() const { return Distinct; }

private:
  /// The slot holding x (of key positionKey(x)), or the empty slot where it would go.
  std::size_t slotOf(std::uint64_t key, const Vec3& x) const;

  PointList Distinct;
  std::vector<long> Numbers;
  std::vector<std::pair<std::uint64_t, long>> Slots; // (key, number), number -1 where empty
  std::uint64_t Mask = 0;
};
} // namespace mlsdeform
