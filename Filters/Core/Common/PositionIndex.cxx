#include "Common/PositionIndex.h"

#include "Common/PositionHash.h"

namespace mlsdeform
{
PositionIndex::PositionIndex(const PointList& positions)
{
  // open addressing with linear probing, at most half full
  std::size_t size = 16;
  while (size < 2 * positions.size())
  {
    size *= 2;
  }
  Slots.assign(size, { 0, -1 });
  Mask = size - 1;
  Numbers.resize(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    const std::uint64_t key = positionKey(positions[i]);
    std::pair<std::uint64_t, long>& slot = Slots[slotOf(key, positions[i])];
    if (slot.second < 0)
    {
      slot = { key, static_cast<long>(Distinct.size()) };
      Distinct.push_back(positions[i]);
    }
    Numbers[i] = slot.second;
  }
}

long PositionIndex::find(const Vec3& x) const
{
  return Slots[slotOf(positionKey(x), x)].second;
}

std::size_t PositionIndex::slotOf(std::uint64_t key, const Vec3& x) const
{
  std::size_t slot = key & Mask;
  // the key's bits, then the coordinates compared exactly
  while (Slots[slot].second >= 0 && !(Slots[slot].first == key && Distinct[Slots[slot].second].cwiseEqual(x).all()))
  {
    slot = (slot + 1) & Mask;
  }
  return slot;
}
} // namespace mlsdeform
