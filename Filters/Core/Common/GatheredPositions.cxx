#include "Common/GatheredPositions.h"

#include <algorithm>
#include <map>
#include <numeric>

namespace mlsdeform
{
namespace
{
bool lexicographicLess(const Vec3& a, const Vec3& b)
{
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}
}

GatheredPositions gatherPositions(const PointList& local, const std::vector<int>& localSets, const Collective& group)
{
  // x, y, z and the set (numbered per process: the process's number in the high bits; a negative
  // one is the same set on every process) per position
  std::vector<double> mine;
  mine.reserve(4 * local.size());
  const double processSets = static_cast<double>(group.rank()) * 4294967296.0;
  for (std::size_t i = 0; i < local.size(); ++i)
  {
    const double set = localSets.empty() ? 0.0 : localSets[i] < 0 ? localSets[i] : processSets + localSets[i];
    mine.insert(mine.end(), { local[i][0], local[i][1], local[i][2], set });
  }
  const std::vector<double> all = group.gather(mine);
  const bool withSets = group.any(!localSets.empty());
  // the indices of each set, each set's sorted by position with equal positions once
  std::map<double, std::vector<long>> sets;
  for (long i = 0; 4 * i < static_cast<long>(all.size()); ++i)
  {
    sets[withSets ? all[4 * i + 3] : 0.0].push_back(i);
  }
  const auto position = [&all](long i) { return Vec3(all[4 * i], all[4 * i + 1], all[4 * i + 2]); };
  std::vector<std::vector<long>> lists;
  for (auto& entry : sets)
  {
    std::vector<long>& list = entry.second;
    const auto less = [&](long a, long b) { return lexicographicLess(position(a), position(b)); };
    if (!std::is_sorted(list.begin(), list.end(), less)) // one process's sorted positions are
    {
      std::stable_sort(list.begin(), list.end(), less);
    }
    list.erase(std::unique(list.begin(), list.end(), [&](long a, long b) { return position(a) == position(b); }), list.end());
    lists.push_back(std::move(list));
  }
  // the sets ordered by their position lists, equal ones once
  const auto listLess = [&](const std::vector<long>& a, const std::vector<long>& b) {
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), [&](long i, long j) { return lexicographicLess(position(i), position(j)); });
  };
  std::stable_sort(lists.begin(), lists.end(), listLess);
  lists.erase(std::unique(lists.begin(), lists.end(), [&](const std::vector<long>& a, const std::vector<long>& b) { return !listLess(a, b) && !listLess(b, a); }),
    lists.end());
  GatheredPositions out;
  out.setCount = std::max<int>(1, static_cast<int>(lists.size()));
  for (std::size_t s = 0; s < lists.size(); ++s)
  {
    for (long i : lists[s])
    {
      out.positions.push_back(position(i));
      out.source.push_back(i);
      if (withSets)
      {
        out.sets.push_back(static_cast<int>(s));
      }
    }
  }
  return out;
}

std::vector<double> gatherValues(const double* local, long count, int components, const GatheredPositions& order,
  const Collective& group)
{
  const std::vector<double> all = group.gather(std::vector<double>(local, local + count * components));
  std::vector<double> out(order.source.size() * static_cast<std::size_t>(components));
  for (std::size_t i = 0; i < order.source.size(); ++i)
  {
    std::copy_n(&all[static_cast<std::size_t>(order.source[i]) * components], components, &out[i * components]);
  }
  return out;
}
}
