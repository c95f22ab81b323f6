#include "Session/DesignSensitivities.h"

#include "Common/GatheredPositions.h"
#include "Vocabulary/FieldNames.h"
#include "Vocabulary/RegionRoles.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cstdint>
#include <numeric>

using namespace mlsdeform;

namespace mlsvtk
{
int DesignTable::column(const std::string& name) const
{
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

DesignTable designTable(const std::vector<RegionInput>& regions)
{
  DesignTable table;
  for (std::size_t c = 0; c < regions.size(); ++c)
  {
    const RegionInput& region = regions[c];
    for (std::size_t v = 0; v < region.variables.size(); ++v)
    {
      const int column = table.column(region.variables[v]);
      if (column < 0)
      {
        table.names.push_back(region.variables[v]);
        table.values.push_back(region.values[v]);
        table.lower.push_back(region.lower[v]);
        table.upper.push_back(region.upper[v]);
      }
      else if (table.values[column] != region.values[v] || table.lower[column] != region.lower[v] || table.upper[column] != region.upper[v])
      {
        throw InvalidInputException("design variable '" + region.variables[v] + "' has the value " + std::to_string(region.values[v]) +
          " and bounds [" + std::to_string(region.lower[v]) + ", " + std::to_string(region.upper[v]) + "] on Regions input #" +
          std::to_string(c) + " but " + std::to_string(table.values[column]) + " and [" + std::to_string(table.lower[column]) + ", " +
          std::to_string(table.upper[column]) + "] on an earlier one: one variable has one value");
      }
    }
  }
  return table;
}

void writeDesignTable(const DesignTable& table, vtkFieldData* field)
{
  vtkNew<vtkStringArray> names;
  names->SetName(fields::DesignVariableNames);
  vtkNew<vtkDoubleArray> values, bounds;
  values->SetName(fields::DesignVariableValues);
  bounds->SetName(fields::DesignVariableBounds);
  bounds->SetNumberOfComponents(2);
  for (std::size_t v = 0; v < table.size(); ++v)
  {
    names->InsertNextValue(table.names[v]);
    values->InsertNextValue(table.values[v]);
    bounds->InsertNextTuple2(table.lower[v], table.upper[v]);
  }
  field->AddArray(names);
  field->AddArray(values);
  field->AddArray(bounds);
}

void PrescribedDerivatives::gather(const std::vector<RegionInput>& regions, const DesignTable& table, const Collective& group)
{
  Variables = table.size();
  Counts.clear();
  Columns.clear();
  Values.clear();
  for (const RegionInput& region : regions)
  {
    if (isConstraint(region.role))
    {
      continue;
    }
    Counts.push_back(static_cast<long>(region.gathered.positions.size()));
    std::vector<int> columns;
    for (const std::string& name : region.variables)
    {
      columns.push_back(table.column(name));
    }
    std::vector<double> values;
    if (!columns.empty())
    {
      const int components = 3 * static_cast<int>(columns.size());
      vtkDataArray* d = region.derivatives;
      std::vector<double> local(static_cast<std::size_t>(d->GetNumberOfTuples()) * components);
      for (vtkIdType i = 0; i < d->GetNumberOfTuples(); ++i)
      {
        d->GetTuple(i, &local[static_cast<std::size_t>(i) * components]);
      }
      values = gatherValues(local.data(), d->GetNumberOfTuples(), components, region.gathered, group);
    }
    Columns.push_back(std::move(columns));
    Values.push_back(std::move(values));
  }
}

std::vector<PointDisplacements> PrescribedDerivatives::along(const std::vector<double>& seeds) const
{
  std::vector<PointDisplacements> out;
  for (std::size_t r = 0; r < Counts.size(); ++r)
  {
    PointDisplacements d = PointDisplacements::Zero(Counts[r], 3);
    const std::size_t m = Columns[r].size();
    for (long i = 0; i < Counts[r]; ++i)
    {
      for (std::size_t v = 0; v < m; ++v)
      {
        const double seed = seeds[Columns[r][v]];
        if (seed != 0)
        {
          for (int c = 0; c < 3; ++c)
          {
            d(i, c) += seed * Values[r][(i * m + v) * 3 + c];
          }
        }
      }
    }
    out.push_back(std::move(d));
  }
  return out;
}

std::vector<double> PrescribedDerivatives::contract(const PointDisplacements& gradient) const
{
  std::vector<double> dJdp(Variables, 0.0);
  long row = 0;
  for (std::size_t r = 0; r < Counts.size(); ++r)
  {
    const std::size_t m = Columns[r].size();
    for (long i = 0; i < Counts[r]; ++i, ++row)
    {
      for (std::size_t v = 0; v < m; ++v)
      {
        for (int c = 0; c < 3; ++c)
        {
          dJdp[Columns[r][v]] += gradient(row, c) * Values[r][(i * m + v) * 3 + c];
        }
      }
    }
  }
  return dJdp;
}

SparseGradients sparseGradient(const std::vector<double>& gradient)
{
  SparseGradients g;
  for (long i = 0; 3 * i + 2 < static_cast<long>(gradient.size()); ++i)
  {
    if (gradient[3 * i] != 0 || gradient[3 * i + 1] != 0 || gradient[3 * i + 2] != 0)
    {
      g.rows.push_back(i);
      g.values.insert(g.values.end(), gradient.begin() + 3 * i, gradient.begin() + 3 * i + 3);
    }
  }
  g.starts.push_back(static_cast<long>(g.rows.size()));
  return g;
}

PositionOrder positionOrder(const PointList& points)
{
  std::vector<long> sorted(points.size());
  std::iota(sorted.begin(), sorted.end(), 0L);
  std::sort(sorted.begin(), sorted.end(), [&](long a, long b) {
    return std::lexicographical_compare(points[a].data(), points[a].data() + 3, points[b].data(), points[b].data() + 3) ||
      (points[a] == points[b] && a < b);
  });
  PositionOrder order;
  order.rank.resize(points.size());
  for (long p : sorted)
  {
    if (order.first.empty() || points[p] != points[order.first.back()])
    {
      order.first.push_back(p);
    }
    order.rank[p] = static_cast<int>(order.first.size()) - 1;
  }
  return order;
}

GatheredGradients gatherGradients(const PointList& points, const PositionOrder& order, const SparseGradients& gradients, const Collective& group)
{
  // this process's positions with a non-zero value, each once, in order: marked by rank, then
  // taken in rank order (no sort)
  const std::size_t m = gradients.functions();
  const auto nonZero = [&](long e) {
    const double* g = gradients.values.data() + 3 * e;
    return g[0] != 0 || g[1] != 0 || g[2] != 0;
  };
  // the ranks hit, as bits (1.26M ranks of the hull case in 160 KB, not a slot array of 5 MB to
  // fill and scan), and a position's place among the local positions by counting the bits below
  std::vector<std::uint64_t> hit((order.first.size() + 63) / 64, 0);
  std::vector<int> entryRank(gradients.rows.size(), -1); // each entry's rank (-1: a zero value)
  for (long e = 0; e < static_cast<long>(gradients.rows.size()); ++e)
  {
    if (nonZero(e))
    {
      const int r = order.rank[gradients.rows[e]];
      entryRank[e] = r;
      hit[r / 64] |= std::uint64_t(1) << (r % 64);
    }
  }
  std::vector<int> below(hit.size()); // the bits set in the words before
  PointList local;
  std::vector<long> first; // the first point at each
  for (std::size_t w = 0; w < hit.size(); ++w)
  {
    below[w] = static_cast<int>(local.size());
    for (std::uint64_t bits = hit[w]; bits; bits &= bits - 1)
    {
      const long r = static_cast<long>(64 * w) + __builtin_ctzll(bits);
      local.push_back(points[order.first[r]]);
      first.push_back(order.first[r]);
    }
  }
  const auto slotOf = [&](int r) {
    return below[r / 64] + __builtin_popcountll(hit[r / 64] & ((std::uint64_t(1) << (r % 64)) - 1));
  };
  const GatheredPositions gathered = gatherPositions(local, {}, group);
  GatheredGradients out;
  out.positions = gathered.positions;
  // both lists sorted by position (gatherPositions sorts as positionOrder does): one merge gives
  // each gathered position's point here (among) and each local position's gathered index where
  // this process's copy is the one gathered (the first process's; the others' sums are dropped)
  const std::vector<std::int64_t> sizes = group.gather(std::vector<std::int64_t>{ static_cast<std::int64_t>(local.size()) });
  const long offset = std::accumulate(sizes.begin(), sizes.begin() + group.rank(), 0L);
  std::vector<long> gatheredOf(local.size(), -1);
  const auto less = [](const Vec3& a, const Vec3& b) { return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3); };
  std::size_t j = 0;
  for (std::size_t i = 0; i < out.positions.size(); ++i)
  {
    while (j < local.size() && less(local[j], out.positions[i]))
    {
      ++j;
    }
    const bool here = j < local.size() && local[j] == out.positions[i];
    out.among.push_back(here ? first[j] : -1);
    if (here && gathered.source[i] == offset + static_cast<long>(j))
    {
      gatheredOf[j] = static_cast<long>(i);
    }
  }
  // per function, the sum of its entries at each of its positions, in the entries' order; its
  // positions in order (a few sorted, many found by a pass over the marks); the gathered copies'
  // non-zero sums kept as (function, gathered position) and values
  std::vector<std::int64_t> keys;
  std::vector<double> sums;
  std::vector<double> sum(3 * local.size(), 0.0);
  std::vector<char> marked(local.size(), 0);
  std::vector<int> touched;
  for (std::size_t f = 0; f < m; ++f)
  {
    touched.clear();
    for (long e = gradients.starts[f]; e < gradients.starts[f + 1]; ++e)
    {
      if (entryRank[e] >= 0)
      {
        const int s = slotOf(entryRank[e]);
        if (!marked[s])
        {
          marked[s] = 1;
          touched.push_back(s);
        }
        for (int c = 0; c < 3; ++c)
        {
          sum[3 * s + c] += gradients.values[3 * e + c];
        }
      }
    }
    if (16 * touched.size() < local.size())
    {
      std::sort(touched.begin(), touched.end());
    }
    else
    {
      touched.clear();
      for (std::size_t s = 0; s < local.size(); ++s)
      {
        if (marked[s])
        {
          touched.push_back(static_cast<int>(s));
        }
      }
    }
    for (const int s : touched)
    {
      double* v = sum.data() + 3 * s;
      if (gatheredOf[s] >= 0 && (v[0] != 0 || v[1] != 0 || v[2] != 0))
      {
        keys.insert(keys.end(), { static_cast<std::int64_t>(f), gatheredOf[s] });
        sums.insert(sums.end(), v, v + 3);
      }
      v[0] = v[1] = v[2] = 0;
      marked[s] = 0;
    }
  }
  // every process's, by function and gathered position (a position's sums come from one process)
  const std::vector<std::int64_t> allKeys = group.gather(keys);
  const std::vector<double> allSums = group.gather(sums);
  std::vector<long> entries(allKeys.size() / 2);
  std::iota(entries.begin(), entries.end(), 0L);
  const auto keyLess = [&](long a, long b) {
    return std::make_pair(allKeys[2 * a], allKeys[2 * a + 1]) < std::make_pair(allKeys[2 * b], allKeys[2 * b + 1]);
  };
  if (!std::is_sorted(entries.begin(), entries.end(), keyLess)) // one process's are
  {
    std::sort(entries.begin(), entries.end(), keyLess);
  }
  out.values.rows.reserve(entries.size());
  out.values.values.reserve(3 * entries.size());
  for (std::size_t f = 0, e = 0; f < m; ++f)
  {
    for (; e < entries.size() && allKeys[2 * entries[e]] == static_cast<std::int64_t>(f); ++e)
    {
      out.values.rows.push_back(allKeys[2 * entries[e] + 1]);
      out.values.values.insert(out.values.values.end(), &allSums[3 * entries[e]], &allSums[3 * entries[e]] + 3);
    }
    out.values.starts.push_back(static_cast<long>(out.values.rows.size()));
  }
  return out;
}
} // namespace mlsvtk
