// The scaled Jacobian of linear and quadratic elements (ElementJacobian.h) on elements whose
// values are known exactly: ideal shapes (1), their mirror images (inverted), straight-sided
// quadratic elements (their linear element's value), and a midside node moved along its edge,
// where the Jacobian along the edge at the corner is (4 s - 1) times the edge (s: the node's
// position along the edge), so that it inverts the element below s = 1/4 with the corners intact.
#include "../TestHarness.h"
#include "Quality/ElementJacobian.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <tuple>
#include <vector>

using namespace mlsdeform;

// The values are a few dozen floating-point operations on coordinates of size <= 2: round-off.
static constexpr double RoundOff = 1e-13;

namespace
{
// Midside nodes at the middle of each edge, appended to the corners.
std::vector<Vec3> withMidsides(std::vector<Vec3> corners, const std::vector<std::pair<int, int>>& edges)
{
  for (const auto& edge : edges)
  {
    corners.push_back((corners[edge.first] + corners[edge.second]) / 2);
  }
  return corners;
}

const std::vector<std::pair<int, int>> TetEdges = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } };
const std::vector<std::pair<int, int>> HexEdges = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 4, 5 }, { 5, 6 },
  { 6, 7 }, { 7, 4 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
const std::vector<std::pair<int, int>> WedgeEdges = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 },
  { 0, 3 }, { 1, 4 }, { 2, 5 } };

// A regular tetrahedron, VTK's order (0 1 2 counter-clockwise seen from 3).
std::vector<Vec3> regularTetrahedron()
{
  return { Vec3(1, 1, 1), Vec3(-1, 1, -1), Vec3(1, -1, -1), Vec3(-1, -1, 1) };
}

std::vector<Vec3> unitCube()
{
  return { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1),
    Vec3(0, 1, 1) };
}

// A right prism of height 1 on the equilateral triangle of side 1, VTK's order: (0 1 2) turns
// clockwise seen from the top (3 4 5).
std::vector<Vec3> rightPrism()
{
  const Vec3 a(0, 0, 0), b(0.5, std::sqrt(0.75), 0), c(1, 0, 0), up(0, 0, 1);
  return { a, b, c, a + up, b + up, c + up };
}

// The mirror image (x -> -x): every element inverted.
std::vector<Vec3> mirrored(std::vector<Vec3> nodes)
{
  for (Vec3& p : nodes)
  {
    p.x() = -p.x();
  }
  return nodes;
}

// A fixed affine map with det > 0 (shear, stretch, rotation): scaled Jacobians change, signs do not.
std::vector<Vec3> sheared(std::vector<Vec3> nodes)
{
  Eigen::Matrix3d map;
  map << 1.3, 0.4, -0.2, 0.1, 0.8, 0.3, 0.2, -0.1, 1.1;
  for (Vec3& p : nodes)
  {
    p = map * p + Vec3(0.5, -1, 2);
  }
  return nodes;
}
} // namespace

TEST(IdealElementsHaveOne)
{
  const std::vector<std::pair<ElementShape, std::vector<Vec3>>> ideal = {
    { ElementShape::Tetra4, regularTetrahedron() },
    { ElementShape::Tetra10, withMidsides(regularTetrahedron(), TetEdges) },
    { ElementShape::Hexa8, unitCube() },
    { ElementShape::Hexa20, withMidsides(unitCube(), HexEdges) },
    { ElementShape::Wedge6, rightPrism() },
    { ElementShape::Wedge15, withMidsides(rightPrism(), WedgeEdges) },
  };
  for (const auto& element : ideal)
  {
    const ElementJacobian j = elementJacobian(element.first, element.second.data());
    CHECK_NEAR(j.minScaled, 1.0, RoundOff);
    CHECK(!j.inverted);
    const ElementJacobian m = elementJacobian(element.first, mirrored(element.second).data());
    CHECK_NEAR(m.minScaled, -1.0, RoundOff);
    CHECK(m.inverted);
  }
}

TEST(StraightSidedQuadraticIsItsLinearElement)
{
  // an affine image: J is constant, so every point (the quadratic's integration points too) has
  // the corners' value
  const std::vector<std::pair<ElementShape, ElementShape>> pairs = { { ElementShape::Tetra4, ElementShape::Tetra10 },
    { ElementShape::Hexa8, ElementShape::Hexa20 }, { ElementShape::Wedge6, ElementShape::Wedge15 } };
  const std::vector<std::vector<Vec3>> shapes = { regularTetrahedron(), unitCube(), rightPrism() };
  const std::vector<std::vector<std::pair<int, int>>> edges = { TetEdges, HexEdges, WedgeEdges };
  for (std::size_t t = 0; t < pairs.size(); ++t)
  {
    const std::vector<Vec3> linear = sheared(shapes[t]);
    const double expected = elementJacobian(pairs[t].first, linear.data()).minScaled;
    CHECK(expected > 0.3 && expected < 0.99); // the shear changed it, and left it valid
    const ElementJacobian quadratic = elementJacobian(pairs[t].second, withMidsides(linear, edges[t]).data());
    CHECK_NEAR(quadratic.minScaled, expected, RoundOff);
    CHECK(!quadratic.inverted);
  }
}

TEST(MidsideNodeInvertsAQuadraticTetrahedron)
{
  // node 4 on edge (0, 1) at x0 + s (x1 - x0): dx along the edge at corner 0 is (4 s - 1)(x1 - x0)
  std::vector<Vec3> nodes = withMidsides(regularTetrahedron(), TetEdges);
  const Vec3 x0 = nodes[0], x1 = nodes[1];
  nodes[4] = x0 + 0.3 * (x1 - x0);
  const ElementJacobian kept = elementJacobian(ElementShape::Tetra10, nodes.data());
  CHECK(!kept.inverted);
  CHECK(kept.minScaled > 0 && kept.minScaled < 1);
  nodes[4] = x0 + 0.2 * (x1 - x0);
  const ElementJacobian folded = elementJacobian(ElementShape::Tetra10, nodes.data());
  CHECK(folded.inverted);
  CHECK(folded.minScaled < 0);
  // the corners alone (the linear element) do not see it
  CHECK_NEAR(elementJacobian(ElementShape::Tetra4, nodes.data()).minScaled, 1.0, RoundOff);
}

TEST(MidsideNodeInvertsAQuadraticHexahedronAndWedge)
{
  // the same along a hexahedron's edge (0, 1) (node 8) and a wedge's vertical edge (0, 3) (node 12)
  for (const auto& c : { std::make_tuple(ElementShape::Hexa20, withMidsides(unitCube(), HexEdges), 8, 0, 1),
         std::make_tuple(ElementShape::Wedge15, withMidsides(rightPrism(), WedgeEdges), 12, 0, 3) })
  {
    std::vector<Vec3> nodes = std::get<1>(c);
    const int node = std::get<2>(c);
    const Vec3 a = nodes[std::get<3>(c)], b = nodes[std::get<4>(c)];
    nodes[node] = a + 0.3 * (b - a);
    CHECK(!elementJacobian(std::get<0>(c), nodes.data()).inverted);
    nodes[node] = a + 0.2 * (b - a);
    const ElementJacobian folded = elementJacobian(std::get<0>(c), nodes.data());
    CHECK(folded.inverted);
    CHECK(folded.minScaled < 0);
  }
}

TEST(ScaledJacobiansAndTheirGradient)
{
  // every shape, distorted (sheared, every node moved by a fixed irregular offset): the frames'
  // least is elementJacobian's, and sum_j w_j d(sj_j)/dX against central differences (h = 1e-6:
  // error h^2 times the third derivative, ~1e-11; round-off 1e-16 / h = 1e-10)
  const std::vector<std::pair<ElementShape, ElementShape>> pairs = { { ElementShape::Tetra4, ElementShape::Tetra10 },
    { ElementShape::Hexa8, ElementShape::Hexa20 }, { ElementShape::Wedge6, ElementShape::Wedge15 } };
  const std::vector<std::vector<Vec3>> shapes = { regularTetrahedron(), unitCube(), rightPrism() };
  const std::vector<std::vector<std::pair<int, int>>> edges = { TetEdges, HexEdges, WedgeEdges };
  for (std::size_t t = 0; t < pairs.size(); ++t)
  {
    for (ElementShape shape : { pairs[t].first, pairs[t].second })
    {
      std::vector<Vec3> nodes = shape == pairs[t].first ? sheared(shapes[t]) : withMidsides(sheared(shapes[t]), edges[t]);
      for (std::size_t n = 0; n < nodes.size(); ++n)
      {
        nodes[n] += 0.08 * Vec3(std::sin(3.1 * n + 1), std::cos(1.7 * n), std::sin(2.3 * n + 0.5));
      }
      std::vector<double> values;
      scaledJacobians(shape, nodes.data(), values);
      CHECK(!values.empty());
      CHECK_NEAR(*std::min_element(values.begin(), values.end()), elementJacobian(shape, nodes.data()).minScaled, 0.0);
      std::vector<double> weights(values.size());
      for (std::size_t j = 0; j < weights.size(); ++j)
      {
        weights[j] = 0.3 + std::sin(1.3 * j);
      }
      auto F = [&](const std::vector<Vec3>& x) {
        std::vector<double> v;
        scaledJacobians(shape, x.data(), v);
        double sum = 0;
        for (std::size_t j = 0; j < v.size(); ++j)
          sum += weights[j] * v[j];
        return sum;
      };
      std::vector<Vec3> exact(nodes.size(), Vec3::Zero());
      addScaledJacobianGradient(shape, nodes.data(), weights.data(), exact.data());
      double worst = 0, scale = 0;
      for (std::size_t n = 0; n < nodes.size(); ++n)
        for (int c = 0; c < 3; ++c)
        {
          std::vector<Vec3> plus = nodes, minus = nodes;
          plus[n][c] += 1e-6;
          minus[n][c] -= 1e-6;
          worst = std::max(worst, std::abs((F(plus) - F(minus)) / 2e-6 - exact[n][c]));
          scale = std::max(scale, std::abs(exact[n][c]));
        }
      std::printf("shape %d: largest |gradient| %.3g, central differences off by %.2g\n", static_cast<int>(shape), scale, worst);
      CHECK(scale > 0.01 && worst <= 1e-8);
    }
  }
}

TEST_MAIN
