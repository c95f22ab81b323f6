// The KS aggregate of checkMesh's non-orthogonality and skewness (FaceQualityAggregate.h): its
// bias bounds, and its gradient at every point against central differences.
#include "../TestHarness.h"
#include "Quality/FaceQualityAggregate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace mlsdeform;

namespace
{
// An nx x ny x nz block of hexahedra, faces listed out of each cell (VTK's order), its points
// moved by a smooth field and a deterministic irregular one (every face skewed and non-orthogonal).
struct Block
{
  PointList points;
  MeshFaces mesh;
  std::vector<int> orientation;
};

// With shear, x also moves by shear z: the layers slide, which skews the top and bottom faces
// (a boundary face's skewness) far more than the faces between the layers.
Block distortedBlock(int nx, int ny, int nz, double shear = 0)
{
  Block b;
  auto v = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
      {
        const double r = std::sin(12.9898 * i + 78.233 * j + 37.719 * k); // in [-1, 1], no pattern
        b.points.push_back(Vec3(i + 0.15 * j + 0.12 * r + shear * k, j + 0.1 * std::sin(i + k) - 0.08 * r, k + 0.05 * i * j + 0.1 * r * r));
      }
  std::vector<CellFaces> cells;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        cells.push_back(CellFaces{ { v(x, y, z), v(x, y, z + 1), v(x, y + 1, z + 1), v(x, y + 1, z) },
          { v(x + 1, y, z), v(x + 1, y + 1, z), v(x + 1, y + 1, z + 1), v(x + 1, y, z + 1) },
          { v(x, y, z), v(x + 1, y, z), v(x + 1, y, z + 1), v(x, y, z + 1) },
          { v(x, y + 1, z), v(x, y + 1, z + 1), v(x + 1, y + 1, z + 1), v(x + 1, y + 1, z) },
          { v(x, y, z), v(x, y + 1, z), v(x + 1, y + 1, z), v(x + 1, y, z) },
          { v(x, y, z + 1), v(x + 1, y, z + 1), v(x + 1, y + 1, z + 1), v(x, y + 1, z + 1) } });
  b.mesh = meshFaces(CellFaceList(cells));
  b.orientation = faceOrientation(b.points, b.mesh);
  return b;
}

// The aggregate on these points, and its gradient when asked.
double aggregate(const Block& b, const PointList& points, QualityMeasure measure, double rho, PointList* gradient, AggregatePart* part = nullptr)
{
  FaceWorkspace work;
  const FaceAggregate a = aggregateFaces(points, b.mesh, b.orientation, measure, rho, work);
  if (part)
  {
    *part = a.part;
  }
  if (gradient)
  {
    gradient->assign(points.size(), Vec3::Zero());
    addAggregateGradient(points, b.mesh, b.orientation, work, a.tail, measure, rho, a.part, *gradient);
  }
  return a.part.value(rho);
}
}

TEST(AggregateBounds)
{
  const Block b = distortedBlock(3, 3, 2);
  for (QualityMeasure measure : { QualityMeasure::NonOrthogonality, QualityMeasure::Skewness })
  {
    FaceMeasures m = faceMeasures(b.points, b.mesh, b.orientation);
    const bool skewness = measure == QualityMeasure::Skewness;
    // the skewness over the interior faces, then the boundary faces'; the non-orthogonality over the interior faces
    std::vector<double> every = skewness ? m.skewness : m.nonOrthogonality;
    if (skewness)
      every.insert(every.end(), m.boundarySkewness.begin(), m.boundarySkewness.end());
    const double largest = measure == QualityMeasure::NonOrthogonality ? m.maxNonOrthogonality : m.maxSkewness;
    for (double rho : { 0.1, 1.0, 10.0, 1000.0 })
    {
      AggregatePart part;
      const double ks = aggregate(b, b.points, measure, rho, nullptr, &part);
      // m <= KS <= m + ln(N) / rho (the sum's terms are at most 1, one of them 1); the largest
      // face is the verdict's to round-off (both the same operations)
      CHECK(part.count == static_cast<long>(every.size()));
      CHECK_NEAR(part.largest, largest, 1e-14 * largest);
      CHECK(ks >= part.largest && ks <= part.largest + std::log(static_cast<double>(part.count)) / rho + 1e-14 * largest);
      // the faces left out (below the largest by (ln N + 46) / rho) change nothing: the sum over
      // every face's measure is the same to round-off (a few ulps of the sum, which is >= 1)
      const AggregatePart all = aggregatePart(every, rho);
      CHECK_NEAR(part.sum, all.sum, 1e-14 * all.sum);
      CHECK_NEAR(part.largest, all.largest, 1e-14 * all.largest);
    }
    // parts combine into the whole: two halves of the faces give the whole's value
    const std::vector<double>& q = every;
    const std::size_t half = q.size() / 2;
    AggregatePart a = aggregatePart(std::vector<double>(q.begin(), q.begin() + half), 3.0);
    a.add(aggregatePart(std::vector<double>(q.begin() + half, q.end()), 3.0), 3.0);
    CHECK_NEAR(a.value(3.0), aggregatePart(q, 3.0).value(3.0), 1e-13 * largest);
  }
}

TEST(AggregateGradientAgainstCentralDifferences)
{
  // Central differences of every coordinate with h and h/2: their error is h^2 |f'''| / 6 (the
  // measures' third derivatives on cells of size 1 are O(100) degrees: 2e-8 at h = 1e-5) plus
  // round-off eps |KS| / h (2e-10); both steps must agree with the exact gradient to 1e-6 of its
  // largest entry, and the smaller step no worse than the larger (up to round-off).
  // The sheared block's most skewed faces are on its top and bottom (checked): the boundary
  // faces' derivatives through their mirrored owner.
  for (const double shear : { 0.0, 0.6 })
  for (QualityMeasure measure : { QualityMeasure::NonOrthogonality, QualityMeasure::Skewness })
  {
    const Block b = distortedBlock(3, 3, 2, shear);
    const double rho = measure == QualityMeasure::NonOrthogonality ? 0.5 : 20.0; // several faces weigh in
    if (shear > 0 && measure == QualityMeasure::Skewness)
    {
      const FaceMeasures m = faceMeasures(b.points, b.mesh, b.orientation);
      const double inside = *std::max_element(m.skewness.begin(), m.skewness.end());
      std::printf("sheared block: largest skewness %.4g on the boundary, %.4g inside\n", m.maxSkewness, inside);
      CHECK(m.maxSkewness > 1.5 * inside);
    }
    PointList exact;
    aggregate(b, b.points, measure, rho, &exact);
    double scale = 0;
    for (const Vec3& g : exact)
      scale = std::max(scale, g.cwiseAbs().maxCoeff());
    CHECK(scale > 0);
    double worst[2] = { 0, 0 };
    for (int s = 0; s < 2; ++s)
    {
      const double h = s == 0 ? 1e-5 : 0.5e-5;
      for (std::size_t p = 0; p < b.points.size(); ++p)
        for (int c = 0; c < 3; ++c)
        {
          PointList plus = b.points, minus = b.points;
          plus[p][c] += h;
          minus[p][c] -= h;
          const double fd = (aggregate(b, plus, measure, rho, nullptr) - aggregate(b, minus, measure, rho, nullptr)) / (2 * h);
          worst[s] = std::max(worst[s], std::abs(fd - exact[p][c]));
        }
    }
    std::printf("%s (shear %g): largest |dKS/dX| %.3g, central differences off by %.2g (h = 1e-5) and %.2g (h = 5e-6)\n",
      measure == QualityMeasure::NonOrthogonality ? "non-orthogonality" : "skewness", shear, scale, worst[0], worst[1]);
    CHECK(worst[0] <= 1e-6 * scale && worst[1] <= 1e-6 * scale);
    CHECK(worst[1] <= worst[0] + 1e-9 * scale);
  }
}

namespace
{
// faceGeometryAdjoint's corner derivatives added at the face's points.
void addFaceAdjoint(const PointList& points, const int* face, std::size_t n, const Vec3& centreBar, const Vec3& areaBar, PointList& gradient)
{
  PointList corners(n, Vec3::Zero());
  faceGeometryAdjoint(points, face, n, centreBar, areaBar, corners.data());
  for (std::size_t k = 0; k < n; ++k)
  {
    gradient[static_cast<std::size_t>(face[k])] += corners[k];
  }
}
}

TEST(GeometryAdjointsAgainstCentralDifferences)
{
  // F = a . centre + b . area of a warped pentagon and of a triangle on some of its points (the
  // direct formula), and of a cell's centre and volume through its faces: the adjoints' gradients
  // against central differences (h = 1e-6: error h^2 |F'''| ~ 1e-12)
  const PointList face = { Vec3(0, 0, 0), Vec3(1.1, 0.1, 0.05), Vec3(1.3, 0.9, -0.1), Vec3(0.5, 1.4, 0.2), Vec3(-0.2, 0.8, 0.0) };
  const Vec3 a(0.3, -0.7, 0.2), bv(0.5, 0.1, -0.4);
  for (const std::vector<int>& ids : { std::vector<int>{ 0, 1, 2, 3, 4 }, std::vector<int>{ 4, 1, 2 } })
  {
    auto F = [&](const PointList& x) {
      const FaceGeometry g = faceGeometry(x, ids);
      return a.dot(g.centre) + bv.dot(g.area);
    };
    PointList exact(5, Vec3::Zero());
    addFaceAdjoint(face, ids.data(), ids.size(), a, bv, exact);
    double worst = 0;
    for (int p = 0; p < 5; ++p)
      for (int c = 0; c < 3; ++c)
      {
        PointList plus = face, minus = face;
        plus[p][c] += 1e-6;
        minus[p][c] -= 1e-6;
        worst = std::max(worst, std::abs((F(plus) - F(minus)) / 2e-6 - exact[p][c]));
      }
    CHECK(worst <= 1e-8);
  }

  const Block b = distortedBlock(1, 1, 1);
  auto G = [&](const PointList& x) {
    const CellGeometry g = cellGeometry(x, std::vector<std::vector<int>>{ { 0, 4, 6, 2 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
      { 0, 2, 3, 1 }, { 4, 5, 7, 6 } });
    return a.dot(g.centre) + 0.7 * g.volume;
  };
  std::vector<std::vector<int>> faces = { { 0, 4, 6, 2 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 2, 3, 1 }, { 4, 5, 7, 6 } };
  std::vector<FaceGeometry> g;
  for (const auto& f : faces)
    g.push_back(faceGeometry(b.points, f));
  std::vector<Vec3> cBar(6, Vec3::Zero()), sBar(6, Vec3::Zero());
  addCellGeometryAdjoint(g, a, 0.7, cBar, sBar);
  PointList cellExact(b.points.size(), Vec3::Zero());
  for (int f = 0; f < 6; ++f)
    addFaceAdjoint(b.points, faces[f].data(), 4, cBar[f], sBar[f], cellExact);
  double worst = 0;
  for (std::size_t p = 0; p < b.points.size(); ++p)
    for (int c = 0; c < 3; ++c)
    {
      PointList plus = b.points, minus = b.points;
      plus[p][c] += 1e-6;
      minus[p][c] -= 1e-6;
      worst = std::max(worst, std::abs((G(plus) - G(minus)) / 2e-6 - cellExact[p][c]));
    }
  CHECK(worst <= 1e-8);
}

TEST_MAIN
