#include "Session/ExactTargets.h"

using namespace mlsdeform;

namespace mlsvtk
{
void ExactTargets::build(const PointList& targets, const PointList& constrained, const PointList& points, double radius, const Progress& progress)
{
  clear();
  PointList stacked = targets;
  stacked.insert(stacked.end(), constrained.begin(), constrained.end());
  Targets = static_cast<long>(targets.size());
  Sites = uniqueSites(stacked, SiteOf);
  SiteCount.assign(Sites.size(), 0.0);
  for (long i = 0; i < Targets; ++i)
  {
    SiteCount[SiteOf[i]] += 1;
  }
  auto blend = std::make_unique<ResidualBlend>(Sites, radius);
  PointRows = subspaceBlocks(*blend, points, nullptr, progress); // rows beyond R stay empty
  Blend = std::move(blend);
}

void ExactTargets::clear()
{
  Blend.reset();
  Sites.clear();
  Targets = 0;
  SiteOf.clear();
  SiteCount.clear();
  PointRows = RowBlocks();
}

PointDisplacements ExactTargets::residuals(const std::vector<PointDisplacementsView>& prescribed, const PointDisplacements& reached) const
{
  PointDisplacements r = PointDisplacements::Zero(static_cast<long>(SiteCount.size()), 3);
  long i = 0;
  for (const PointDisplacementsView& dbar : prescribed)
  {
    for (long j = 0; j < dbar.rows(); ++j, ++i)
    {
      r.row(SiteOf[i]) += (dbar.row(j) - reached.row(i)) / SiteCount[SiteOf[i]];
    }
  }
  return r;
}

std::vector<double> ExactTargets::misses(
  const std::vector<PointDisplacementsView>& prescribed, const PointDisplacements& reached, const PointDisplacements& r) const
{
  std::vector<double> miss;
  long i = 0;
  for (const PointDisplacementsView& dbar : prescribed)
  {
    for (long j = 0; j < dbar.rows(); ++j, ++i)
    {
      miss.push_back((dbar.row(j) - reached.row(i) - r.row(SiteOf[i])).norm());
    }
  }
  return miss;
}

void ExactTargets::add(const PointDisplacements& r, long begin, long end, double* out) const
{
  multiplyRows(PointRows, r, begin, end, out, Into::Add); // the blend's rows, by block
}

GatheredRows ExactTargets::rowsAt(const PointList& positions, std::vector<long> among, bool storageOrder) const
{
  return gatherRows(*Blend, positions, { &PointRows, std::move(among) }, nullptr, {}, storageOrder);
}

std::vector<PointDisplacements> ExactTargets::pull(const GatheredRows& rows, const mlsdeform::SparseGradients& g) const
{
  return multiplyTransposedEach(rows, g);
}

PointDisplacements ExactTargets::targetShare(const PointDisplacements& h) const
{
  PointDisplacements e(Targets, 3);
  for (long i = 0; i < Targets; ++i)
  {
    e.row(i) = h.row(SiteOf[i]) / SiteCount[SiteOf[i]];
  }
  return e;
}
} // namespace mlsvtk
