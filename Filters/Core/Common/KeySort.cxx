#include "Common/KeySort.h"

namespace mlsdeform
{
namespace
{
// Bits of the key sorted by one pass: 2048 counters stay in the first-level cache.
constexpr int DigitBits = 11;
constexpr std::uint64_t Digits = std::uint64_t(1) << DigitBits;
}

void sortByKey(std::vector<std::pair<std::uint64_t, long>>& items, int bits)
{
  std::vector<std::pair<std::uint64_t, long>> sorted(items.size());
  for (int shift = 0; shift < bits; shift += DigitBits)
  {
    std::vector<std::size_t> start(Digits + 1, 0);
    for (const auto& item : items)
    {
      ++start[((item.first >> shift) & (Digits - 1)) + 1];
    }
    for (std::uint64_t d = 0; d < Digits; ++d)
    {
      start[d + 1] += start[d];
    }
    for (const auto& item : items)
    {
      sorted[start[(item.first >> shift) & (Digits - 1)]++] = item;
    }
    items.swap(sorted);
  }
}

int keyBits(std::uint64_t keys)
{
  int bits = 0;
  for (std::uint64_t largest = keys > 0 ? keys - 1 : 0; largest > 0; largest >>= 1)
  {
    ++bits;
  }
  return bits;
}
} // namespace mlsdeform
