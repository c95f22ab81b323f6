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
    std::uint64_t slot = key & Mask;
    while (Slots[slot].second >= 0 && !(Slots[slot].first == key && Distinct[Slots[slot].second].cwiseEqual(positions[i]).all()))
    {
      slot = (slot + 1) & Mask;
    }
    if (Slots[slot].second < 0)
    {
      Slots[slot] = { key, static_cast<long>(Distinct.size()) };
      Distinct.push_back(positions[i]);
    }
    Numbers[i] = Slots[slot].second;
  }
}

long PositionIndex::find(const Vec3& x) const
{
  const std::uint64_t key = positionKey(x);
  for (std::uint64_t slot = key & Mask; Slots[slot].second >= 0; slot = (slot + 1) & Mask)
  {
    if (Slots[slot].first == key && Distinct[Slots[slot].second].cwiseEqual(x).all()) // the key's bits, compared exactly
    {
      return Slots[slot].second;
    }
  }
  return -1;
}
} // namespace mlsdeform
