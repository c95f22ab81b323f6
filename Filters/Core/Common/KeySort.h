// Sorting by integer keys in linear time: the spatial searches sort their samples by cell or
// Morton code, thousands of times per detection.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace mlsdeform
{
/// Sorts (key, value) pairs by key, stably (equal keys keep their order, so ties stay in the
/// order given): a least-significant-digit radix sort over the keys' lowest `bits` bits, whose
/// higher bits must be zero.
void sortByKey(std::vector<std::pair<std::uint64_t, long>>& items, int bits);

/// The number of bits that hold every key below `keys` (0 for keys <= 1).
int keyBits(std::uint64_t keys);
} // namespace mlsdeform
