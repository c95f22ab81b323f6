#include "Common/IdIndex.h"

#include <algorithm>

namespace mlsformats
{
IdIndex::IdIndex(const std::vector<std::int64_t>& ids)
{
  if (ids.empty())
  {
    return;
  }
  const auto [low, high] = std::minmax_element(ids.begin(), ids.end());
  // a table when it is at most 4 entries an id (and positions fit its 32 bits)
  const std::uint64_t range = static_cast<std::uint64_t>(*high) - static_cast<std::uint64_t>(*low);
  if (range < 4 * ids.size() + 1024 && ids.size() < 0xffffffffu)
  {
    this->Low = *low;
    this->Dense.assign(range + 1, 0);
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
      std::uint32_t& slot = this->Dense[ids[i] - this->Low];
      if (slot != 0 && this->duplicate == none)
      {
        this->duplicate = i;
      }
      slot = static_cast<std::uint32_t>(i + 1);
    }
    return;
  }
  this->Sparse.reserve(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    if (!this->Sparse.emplace(ids[i], i).second && this->duplicate == none)
    {
      this->duplicate = i;
    }
  }
}

std::size_t IdIndex::find(std::int64_t id) const
{
  if (!this->Dense.empty())
  {
    const std::uint64_t offset = static_cast<std::uint64_t>(id) - static_cast<std::uint64_t>(this->Low);
    return offset < this->Dense.size() ? static_cast<std::size_t>(this->Dense[offset]) - 1 : none;
  }
  const auto found = this->Sparse.find(id);
  return found == this->Sparse.end() ? none : found->second;
}
} // namespace mlsformats
