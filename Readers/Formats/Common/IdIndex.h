// Where each id of a file's nodes or elements is in their list: a table when the ids are dense (as
// meshers write them), a hash map otherwise.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace mlsformats
{
class IdIndex
{
public:
  static constexpr std::size_t none = static_cast<std::size_t>(-1);
  explicit IdIndex(const std::vector<std::int64_t>& ids);
  /// The position of id, or none.
  std::size_t find(std::int64_t id) const;
  /// The first id found twice (its second position), or none.
  std::size_t duplicate = none;

private:
  std::int64_t Low = 0;
  std::vector<std::uint32_t> Dense; // position + 1, 0 for none
  std::unordered_map<std::int64_t, std::size_t> Sparse;
};
} // namespace mlsformats
