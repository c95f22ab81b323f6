// Random numbers keyed by positions: an element of a mesh draws the same numbers wherever it is
// stored (on any process, at any index, its vertices in any order), so that sampling a mesh split
// over processes gives what sampling it whole gives. splitmix64 (Steele, Lea, Flood 2014) mixes
// the coordinates' bits; its sequence is the generator.
#pragma once

#include "Common/CoreTypes.h"

#include <cstdint>
#include <cstring>

namespace mlsdeform
{
/// splitmix64's finalizer: a bijective mix of 64 bits.
inline std::uint64_t mixBits(std::uint64_t x)
{
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// A key of a position's exact coordinates (+0 and -0 alike).
inline std::uint64_t positionKey(const Vec3& x)
{
  std::uint64_t key = 0;
  for (int c = 0; c < 3; ++c)
  {
    const double value = x[c] == 0 ? 0.0 : x[c];
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    key = mixBits(key + bits + 0x9e3779b97f4a7c15ULL);
  }
  return key;
}

/// Uniform numbers in [0, 1) from a key (splitmix64's sequence started at the mixed key).
class KeyedRandom
{
public:
  explicit KeyedRandom(std::uint64_t key)
    : State(mixBits(key))
  {
  }
  double uniform()
  {
    State += 0x9e3779b97f4a7c15ULL;
    return static_cast<double>(mixBits(State) >> 11) * 0x1.0p-53;
  }

private:
  std::uint64_t State;
};
} // namespace mlsdeform
