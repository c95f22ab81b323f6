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
  std::vector<int> slot(order.first.size(), -1); // a position's place among the local positions
  for (long e = 0; e < static_cast<long>(gradients.rows.size()); ++e)
  {
    if (nonZero(e))
    {
      slot[order.rank[gradients.rows[e]]] = 0;
    }
  }
  PointList local;
  std::vector<long> first; // the first point at each
  for (std::size_t r = 0; r < slot.size(); ++r)
  {
    if (slot[r] == 0)
    {
      slot[r] = static_cast<int>(local.size());
      local.push_back(points[order.first[r]]);
      first.push_back(order.first[r]);
    }
  }
  const GatheredPositions gathered = gatherPositions(local, {}, group);
  GatheredGradients out;
  out.positions = gathered.positions;
  // both lists sorted by position (gatherPositions sorts as positionOrder does): one merge
  const auto less = [](const Vec3& a, const Vec3& b) { return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3); };
  std::size_t j = 0;
  for (const Vec3& x : out.positions)
  {
    while (j < local.size() && less(local[j], x))
    {
      ++j;
    }
    out.among.push_back(j < local.size() && local[j] == x ? first[j] : -1);
  }
  // per function, the sum of its entries at each position, in the entries' order
  for (std::size_t f = 0; f < m; ++f)
  {
    PointDisplacements sums = PointDisplacements::Zero(static_cast<long>(local.size()), 3);
    for (long e = gradients.starts[f]; e < gradients.starts[f + 1]; ++e)
    {
      if (nonZero(e))
      {
        sums.row(slot[order.rank[gradients.rows[e]]]) += Eigen::Map<const Eigen::RowVector3d>(gradients.values.data() + 3 * e);
      }
    }
    const std::vector<double> values = gatherValues(sums.data(), sums.rows(), 3, gathered, group);
    out.values.push_back(Eigen::Map<const PointDisplacements>(values.data(), static_cast<long>(gathered.positions.size()), 3));
  }
  return out;
}
} // namespace mlsvtk
