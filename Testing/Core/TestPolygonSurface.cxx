// The enclosed volume and the area of a polygon surface (PolygonSurface.h): exact on a box, its
// open extruded form along an axis, the gradients against central differences, the same bits on
// one and two threads, and bad input refused.
#include "../TestHarness.h"
#include "Quality/PolygonSurface.h"

#include <omp.h>

#include <cmath>
#include <cstdio>

using namespace mlsdeform;

namespace
{
// The box [0, size.x] x [0, size.y] x [0, size.z], each side an n x n grid of quadrilaterals (every
// other one split into two triangles) with its own points, oriented outwards; without the sides
// normal to z when open (the extruded shape's front and back). The points start after `before`
// points of the list (the surface on some of a mesh's points).
struct Box
{
  PointList points;
  std::vector<long> starts{ 0 };
  std::vector<int> corners;
};

Box box(const Vec3& size, int n, bool open, int before)
{
  Box b;
  b.points.assign(static_cast<std::size_t>(before), Vec3(7, 7, 7));
  // the sides' outward normal axis k and sign, in-plane axes i, j with e_i x e_j = the normal
  const int sides[6][4] = { { 0, 1, 1, 2 }, { 0, -1, 2, 1 }, { 1, 1, 2, 0 }, { 1, -1, 0, 2 }, { 2, 1, 0, 1 }, { 2, -1, 1, 0 } };
  for (const auto& side : sides)
  {
    const int k = side[0], sign = side[1], i = side[2], j = side[3];
    if (open && k == 2)
    {
      continue;
    }
    const int first = static_cast<int>(b.points.size());
    for (int v = 0; v <= n; ++v)
      for (int u = 0; u <= n; ++u)
      {
        Vec3 x = Vec3::Zero();
        x[k] = sign > 0 ? size[k] : 0;
        x[i] = size[i] * u / n;
        x[j] = size[j] * v / n;
        b.points.push_back(x);
      }
    auto at = [&](int u, int v) { return first + u + (n + 1) * v; };
    for (int v = 0; v < n; ++v)
      for (int u = 0; u < n; ++u)
      {
        const int q[4] = { at(u, v), at(u + 1, v), at(u + 1, v + 1), at(u, v + 1) };
        const std::vector<std::vector<int>> polygons = (u + v) % 2 ? std::vector<std::vector<int>>{ { q[0], q[1], q[2] }, { q[0], q[2], q[3] } }
                                                                   : std::vector<std::vector<int>>{ { q[0], q[1], q[2], q[3] } };
        for (const std::vector<int>& p : polygons)
        {
          b.corners.insert(b.corners.end(), p.begin(), p.end());
          b.starts.push_back(static_cast<long>(b.corners.size()));
        }
      }
  }
  return b;
}

// The points moved by a smooth field and a deterministic irregular one (warped faces).
PointList warped(const PointList& points)
{
  PointList out = points;
  for (std::size_t p = 0; p < out.size(); ++p)
  {
    const double r = std::sin(12.9898 * static_cast<double>(p) + 0.5);
    out[p] += Vec3(0.1 * std::sin(out[p].y() + 0.3 * out[p].z()) + 0.03 * r, 0.05 * out[p].x() * out[p].z() - 0.02 * r, 0.04 * r * r);
  }
  return out;
}

// The largest difference of gradient (at surface.points()) from central differences of F (step h).
template <typename Function>
double worstDifference(const PolygonSurface& surface, const PointList& points, const PointList& gradient, Function F, double h)
{
  double worst = 0;
  for (std::size_t i = 0; i < surface.points().size(); ++i)
    for (int c = 0; c < 3; ++c)
    {
      PointList plus = points, minus = points;
      plus[static_cast<std::size_t>(surface.points()[i])][c] += h;
      minus[static_cast<std::size_t>(surface.points()[i])][c] -= h;
      worst = std::max(worst, std::abs((F(plus) - F(minus)) / (2 * h) - gradient[i][c]));
    }
  return worst;
}

const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
}

TEST(VolumeAndAreaOfABox)
{
  // sums of a few hundred terms of size <= 3: round-off 1e-13 at most
  const Box b = box(Vec3(2, 1, 3), 4, false, 5);
  const PolygonSurface surface(b.starts, b.corners);
  CHECK(surface.points().size() == 6 * 25 && surface.points().front() == 5);
  CHECK_NEAR(surface.volume(b.points, I, 1.0 / 3, nullptr), 6.0, 1e-13);
  CHECK_NEAR(surface.area(b.points, nullptr), 2 * (2 + 6 + 3), 1e-13);
  // the other orientation: the volume's sign turns, the area stays
  std::vector<int> reversed = b.corners;
  for (std::size_t f = 0; f + 1 < b.starts.size(); ++f)
  {
    std::reverse(reversed.begin() + b.starts[f], reversed.begin() + b.starts[f + 1]);
  }
  const PolygonSurface inward(b.starts, reversed);
  CHECK_NEAR(inward.volume(b.points, I, 1.0 / 3, nullptr), -6.0, 1e-13);
  CHECK_NEAR(inward.area(b.points, nullptr), 22.0, 1e-13);
}

TEST(ExtrudedShapeOpenAlongItsAxis)
{
  // without the front and back: the in-plane field's flux, 1/2 sum (P C) . S = the cross-section
  // (2 x 1) times the depth 3; the closed formula is wrong on it (an open surface)
  const Box b = box(Vec3(2, 1, 3), 3, true, 0);
  const PolygonSurface surface(b.starts, b.corners);
  const Vec3 z(0, 0, 1);
  CHECK_NEAR(surface.volume(b.points, I - z * z.transpose(), 0.5, nullptr), 6.0, 1e-13);
  CHECK(std::abs(surface.volume(b.points, I, 1.0 / 3, nullptr) - 6.0) > 0.1);
}

TEST(GradientsAgainstCentralDifferences)
{
  // F'' of a sum of products of coordinates of size ~3: h = 1e-6 leaves h^2 |F'''| ~ 1e-12 and
  // round-off eps |F| / h ~ 1e-9; h and h/2 agree with the exact gradient to 1e-7
  const Box b = box(Vec3(2, 1, 3), 2, false, 3);
  const PointList x = warped(b.points);
  const PolygonSurface surface(b.starts, b.corners);
  const Vec3 a = Vec3(0.2, 0.1, 1).normalized();
  const Eigen::Matrix3d P = I - a * a.transpose();
  PointList volume, extruded, area;
  surface.volume(x, I, 1.0 / 3, &volume);
  surface.volume(x, P, 0.5, &extruded);
  surface.area(x, &area);
  CHECK(volume.size() == surface.points().size());
  for (double h : { 1e-6, 5e-7 })
  {
    CHECK(worstDifference(surface, x, volume, [&](const PointList& y) { return surface.volume(y, I, 1.0 / 3, nullptr); }, h) <= 1e-7);
    CHECK(worstDifference(surface, x, extruded, [&](const PointList& y) { return surface.volume(y, P, 0.5, nullptr); }, h) <= 1e-7);
    CHECK(worstDifference(surface, x, area, [&](const PointList& y) { return surface.area(y, nullptr); }, h) <= 1e-7);
  }
}

TEST(SameBitsOnOneAndTwoThreads)
{
  // the faces' values summed in face order, each point's terms in corner order
  const Box b = box(Vec3(2, 1, 3), 40, false, 0);
  const PointList x = warped(b.points);
  const PolygonSurface surface(b.starts, b.corners);
  std::vector<double> volumes;
  std::vector<PointList> gradients;
  const int threads = omp_get_max_threads();
  for (int t : { 1, 2 })
  {
    omp_set_num_threads(t);
    gradients.emplace_back();
    volumes.push_back(surface.volume(x, I, 1.0 / 3, &gradients.back()));
    gradients.emplace_back();
    volumes.push_back(surface.area(x, &gradients.back()));
  }
  omp_set_num_threads(threads);
  CHECK(volumes[0] == volumes[2] && volumes[1] == volumes[3]);
  CHECK(gradients[0] == gradients[2] && gradients[1] == gradients[3]);
}

TEST(BadInputIsRefused)
{
  CHECK_THROWS(PolygonSurface({ 0, 3 }, { 0, 1 }), InvalidInputException);      // starts past the corners
  CHECK_THROWS(PolygonSurface({ 0, 3, 2 }, { 0, 1, 2 }), InvalidInputException); // not ascending
  CHECK_THROWS(PolygonSurface({ 0, 3 }, { 0, -1, 2 }), InvalidInputException);  // a negative point
  const PolygonSurface surface({ 0, 3 }, { 0, 1, 5 });
  CHECK_THROWS(surface.area(PointList(5, Vec3::Zero()), nullptr), InvalidInputException); // point 5 missing
  const PolygonSurface none({ 0 }, {});
  CHECK(none.polygons() == 0 && none.area(PointList(), nullptr) == 0);
}

TEST_MAIN
