#include "Basis/ResidualBlend.h"

#include "Common/BoundingBox.h"

#include <cmath>

namespace mlsdeform
{
namespace
{
// K, the sites a position's interpolation uses: enough for a smooth mean over a region's
// neighbouring points in 3D, few enough to keep the rows short (K entries per point).
constexpr int Neighbours = 8;

double fade(double t) // beta(t) of the header
{
  return t >= 1 ? 0.0 : std::pow(1 - t, 4) * (4 * t + 1);
}
}

ResidualBlend::ResidualBlend(const PointList& sites, double radius)
  : Radius(radius)
  , Sites(sites)
{
  if (sites.empty() || !(radius > 0) || !std::isfinite(radius))
  {
    throw InvalidInputException("exact targets need target points and a positive, finite blend radius");
  }
  requireFinite(sites, "target points");
  if (Sites.distinct().size() != sites.size())
  {
    throw InvalidInputException("the exact targets' sites must be distinct positions (uniqueSites)");
  }
  Tree.build(sites);
}

void ResidualBlend::evaluate(const Vec3& x, ShapeFunctionValues& out, bool) const
{
  out.index.clear();
  out.value.clear();
  out.gradient.clear();
  out.laplacian.clear();
  // at a site: its own residual, exactly (a region's points are sites: a fifth of a CFD case's
  // points, each spared the search)
  if (const long site = Sites.find(x); site >= 0)
  {
    out.index.push_back(static_cast<int>(site));
    out.value.push_back(1.0);
    return;
  }
  thread_local std::vector<int> nearest;
  thread_local std::vector<double> squared;
  Tree.kNearest(x, Neighbours + 1, nearest, squared);
  if (nearest.empty() || squared[0] >= Radius * Radius)
  {
    return;
  }
  // all sites when there are no more than K (no (K+1)-th to taper towards)
  const std::size_t used = nearest.size() > Neighbours ? Neighbours : nearest.size();
  const double taper = nearest.size() > Neighbours ? std::sqrt(squared[Neighbours]) : 0.0;
  double sum = 0;
  for (std::size_t a = 0; a < used; ++a)
  {
    const double d = std::sqrt(squared[a]);
    const double omega = (taper > 0 ? std::pow(1 - d / taper, 2) : 1.0) / squared[a];
    out.index.push_back(nearest[a]);
    out.value.push_back(omega);
    sum += omega;
  }
  if (!(sum > 0)) // the K+1 nearest all equally far: their plain inverse-distance mean
  {
    for (std::size_t a = 0; a < used; ++a)
    {
      out.value[a] = 1 / squared[a];
      sum += out.value[a];
    }
  }
  std::size_t kept = 0; // sites beyond R drop out
  for (std::size_t a = 0; a < used; ++a)
  {
    const double value = out.value[a] * fade(std::sqrt(squared[a]) / Radius) / sum;
    if (value > 0)
    {
      out.index[kept] = out.index[a];
      out.value[kept++] = value;
    }
  }
  out.index.resize(kept);
  out.value.resize(kept);
}

PointList uniqueSites(const PointList& positions, std::vector<long>& siteOf)
{
  const PositionIndex index(positions);
  siteOf = index.numbers();
  return index.distinct();
}
} // namespace mlsdeform
