#include "Quality/PolygonSurface.h"

#include "Quality/FaceQuality.h"
#include "Quality/FaceQualityAggregate.h"

#include <algorithm>
#include <numeric>

namespace mlsdeform
{
PolygonSurface::PolygonSurface(const std::vector<long>& starts, const std::vector<int>& corners)
  : Points(corners), Starts(starts), Corners(corners.size())
{
  if (Starts.empty() || Starts.front() != 0 || Starts.back() != static_cast<long>(corners.size()) ||
      !std::is_sorted(Starts.begin(), Starts.end()) ||
      std::any_of(corners.begin(), corners.end(), [](int p) { return p < 0; }))
  {
    throw InvalidInputException("a polygon surface needs ascending polygon starts from 0 to its corners' number and point indices >= 0");
  }
  std::sort(Points.begin(), Points.end());
  Points.erase(std::unique(Points.begin(), Points.end()), Points.end());
  std::vector<long> count(Points.size() + 1, 0);
  for (std::size_t k = 0; k < corners.size(); ++k)
  {
    Corners[k] = static_cast<int>(std::lower_bound(Points.begin(), Points.end(), corners[k]) - Points.begin());
    ++count[static_cast<std::size_t>(Corners[k]) + 1];
  }
  std::partial_sum(count.begin(), count.end(), count.begin());
  CornersOfStart = count;
  CornersOf.resize(corners.size());
  for (std::size_t k = 0; k < corners.size(); ++k) // in corner order: ascending per point
  {
    CornersOf[static_cast<std::size_t>(count[static_cast<std::size_t>(Corners[k])]++)] = static_cast<long>(k);
  }
}

template <typename Term>
double PolygonSurface::sum(const PointList& points, Term term, PointList* gradient) const
{
  if (points.size() < pointsNeeded())
  {
    throw InvalidInputException("a polygon surface's point " + std::to_string(pointsNeeded() - 1) + " is not among the " +
                                std::to_string(points.size()) + " points");
  }
  const long m = static_cast<long>(polygons());
  const long np = static_cast<long>(Points.size());
  PointList local(Points.size()); // the surface's points alone, in Points' order
#pragma omp parallel for schedule(static)
  for (long i = 0; i < np; ++i)
  {
    local[static_cast<std::size_t>(i)] = points[static_cast<std::size_t>(Points[static_cast<std::size_t>(i)])];
  }
  std::vector<double> values(static_cast<std::size_t>(m));
  PointList cornerBar(gradient ? Corners.size() : 0, Vec3::Zero()); // dF/dX per corner
#pragma omp parallel for schedule(static)
  for (long f = 0; f < m; ++f)
  {
    const auto start = static_cast<std::size_t>(Starts[static_cast<std::size_t>(f)]);
    const auto n = static_cast<std::size_t>(Starts[static_cast<std::size_t>(f) + 1]) - start;
    const FaceGeometry g = faceGeometry(local, Corners.data() + start, n);
    Vec3 centreBar = Vec3::Zero(), areaBar = Vec3::Zero();
    values[static_cast<std::size_t>(f)] = term(g, centreBar, areaBar);
    if (gradient)
    {
      faceGeometryAdjoint(local, Corners.data() + start, n, centreBar, areaBar, cornerBar.data() + start);
    }
  }
  if (gradient)
  {
    gradient->assign(Points.size(), Vec3::Zero());
#pragma omp parallel for schedule(static)
    for (long i = 0; i < np; ++i)
    {
      Vec3& g = (*gradient)[static_cast<std::size_t>(i)];
      for (long c = CornersOfStart[static_cast<std::size_t>(i)]; c < CornersOfStart[static_cast<std::size_t>(i) + 1]; ++c)
      {
        g += cornerBar[static_cast<std::size_t>(CornersOf[static_cast<std::size_t>(c)])];
      }
    }
  }
  return std::accumulate(values.begin(), values.end(), 0.0); // in face order
}

double PolygonSurface::volume(const PointList& points, const Eigen::Matrix3d& P, double alpha, PointList* gradient) const
{
  // alpha (P C) . S: d/dC = alpha P S, d/dS = alpha P C
  return sum(points, [&](const FaceGeometry& g, Vec3& centreBar, Vec3& areaBar) {
    const Vec3 PC = P * g.centre;
    centreBar = alpha * (P * g.area);
    areaBar = alpha * PC;
    return alpha * PC.dot(g.area);
  }, gradient);
}

double PolygonSurface::area(const PointList& points, PointList* gradient) const
{
  // |S|: d/dS = S / |S|
  return sum(points, [&](const FaceGeometry& g, Vec3&, Vec3& areaBar) {
    const double a = g.area.norm();
    if (a > 0)
    {
      areaBar = g.area / a;
    }
    return a;
  }, gradient);
}
} // namespace mlsdeform
