// The solid elements (SolidElements.h) and their exact shape derivatives (ShapeSensitivity.h), for
// each of C3D4, C3D10, C3D8, C3D20, C3D20R, C3D6, C3D15 on distorted elements (curved edges where
// the element has midside nodes): the shape functions are a partition of unity, 1 at their own
// node and 0 at the others; the integration weights sum to the reference volume; a uniform strain
// passes the patch test (its work is V a(E, F) exactly) and a rigid motion does no work; and the
// derivatives of the work lambda^T K_e u and of the volume agree with central differences.
#include "../TestHarness.h"
#include "Structural/ShapeSensitivity.h"

#include <Eigen/Dense>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

using namespace mlsdeform;

namespace
{
const std::vector<SolidElement> Elements = { SolidElement::C3D4, SolidElement::C3D10, SolidElement::C3D8, SolidElement::C3D20,
  SolidElement::C3D20R, SolidElement::C3D6, SolidElement::C3D15 };

// A deterministic sequence in [-1, 1] (a linear congruential generator: the same on every machine).
struct Sequence
{
  unsigned long long state;
  double next()
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / static_cast<double>(1ULL << 53) * 2 - 1;
  }
  Vec3 vector() { return Vec3(next(), next(), next()); }
};

// The nodes' reference coordinates, VTK's order: corners, then the edges' midpoints.
std::vector<Vec3> referenceNodes(SolidElement element)
{
  std::vector<Vec3> corners;
  std::vector<std::pair<int, int>> edges;
  switch (element)
  {
    case SolidElement::C3D4:
    case SolidElement::C3D10:
      corners = { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1) };
      edges = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } };
      break;
    case SolidElement::C3D8:
    case SolidElement::C3D20:
    case SolidElement::C3D20R:
      corners = { Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(1, 1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1), Vec3(1, -1, 1),
        Vec3(1, 1, 1), Vec3(-1, 1, 1) };
      edges = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 4 }, { 0, 4 }, { 1, 5 }, { 2, 6 },
        { 3, 7 } };
      break;
    case SolidElement::C3D6:
    case SolidElement::C3D15:
      corners = { Vec3(0, 0, -1), Vec3(1, 0, -1), Vec3(0, 1, -1), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1) };
      edges = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 }, { 0, 3 }, { 1, 4 }, { 2, 5 } };
      break;
  }
  std::vector<Vec3> nodes = corners;
  for (int e = 0; static_cast<int>(nodes.size()) < nodeCount(element); ++e)
  {
    nodes.push_back((corners[edges[e].first] + corners[edges[e].second]) / 2);
  }
  return nodes;
}

double referenceVolume(SolidElement element)
{
  switch (element)
  {
    case SolidElement::C3D4:
    case SolidElement::C3D10: return 1 / 6.0;
    case SolidElement::C3D6:
    case SolidElement::C3D15: return 1;
    default: return 8;
  }
}

// A distorted element: the reference nodes through a general linear map, each node moved by up
// to 8% of the element's size (midside nodes too: curved edges), and shifted.
std::vector<Vec3> distorted(SolidElement element, Sequence& random)
{
  Eigen::Matrix3d M;
  M << 1.3, 0.2, -0.1, 0.15, 0.9, 0.25, -0.05, 0.3, 1.1;
  std::vector<Vec3> X;
  for (const Vec3& xi : referenceNodes(element))
  {
    X.push_back(M * xi + 0.08 * random.vector() + Vec3(2, -1, 0.5));
  }
  return X;
}

const IsotropicElastic Steel{ 210000, 0.3 };
} // namespace

TEST(ShapeFunctionsArePartitionsOfUnity)
{
  for (SolidElement element : Elements)
  {
    const int n = nodeCount(element);
    const std::vector<Vec3> nodes = referenceNodes(element);
    std::vector<double> N(n);
    std::vector<Vec3> dN(n);
    for (const IntegrationPoint& point : integrationPoints(element))
    {
      shapeFunctions(element, point.xi, N.data(), dN.data());
      double sum = 0;
      Vec3 gradientSum = Vec3::Zero(), position = Vec3::Zero();
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int a = 0; a < n; ++a)
      {
        sum += N[a];
        gradientSum += dN[a];
        position += N[a] * nodes[a];
        J += nodes[a] * dN[a].transpose();
      }
      CHECK_NEAR(sum, 1.0, 1e-14);
      CHECK_NEAR(gradientSum.norm(), 0.0, 1e-14);
      // the reference element maps onto itself: x(xi) = xi, J = I
      CHECK_NEAR((position - point.xi).norm(), 0.0, 1e-14);
      CHECK_NEAR((J - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
    }
    for (int b = 0; b < n; ++b) // 1 at the node's own position, 0 at the others'
    {
      shapeFunctions(element, nodes[b], N.data(), dN.data());
      for (int a = 0; a < n; ++a)
      {
        CHECK_NEAR(N[a], a == b ? 1.0 : 0.0, 1e-14);
      }
    }
  }
}

TEST(ShapeGradientsAreTheShapeFunctionsDerivatives)
{
  // central differences of N with h = 1e-5: the shape functions are polynomials of degree <= 3,
  // the error h^2 / 6 |N'''| <= 1e-9
  Sequence random{ 3 };
  for (SolidElement element : Elements)
  {
    const int n = nodeCount(element);
    std::vector<double> N(n), plus(n), minus(n);
    std::vector<Vec3> dN(n), ignored(n);
    const Vec3 xi = integrationPoints(element).front().xi + 0.05 * random.vector();
    shapeFunctions(element, xi, N.data(), dN.data());
    const double h = 1e-5;
    for (int d = 0; d < 3; ++d)
    {
      Vec3 step = Vec3::Zero();
      step[d] = h;
      shapeFunctions(element, xi + step, plus.data(), ignored.data());
      shapeFunctions(element, xi - step, minus.data(), ignored.data());
      for (int a = 0; a < n; ++a)
      {
        CHECK_NEAR(dN[a][d], (plus[a] - minus[a]) / (2 * h), 1e-8);
      }
    }
  }
}

TEST(IntegrationWeightsSumToTheVolume)
{
  Eigen::Matrix3d M;
  M << 1.3, 0.2, -0.1, 0.15, 0.9, 0.25, -0.05, 0.3, 1.1;
  for (SolidElement element : Elements)
  {
    double sum = 0;
    for (const IntegrationPoint& point : integrationPoints(element))
    {
      sum += point.weight;
    }
    CHECK_NEAR(sum, referenceVolume(element), 1e-14);
    std::vector<Vec3> X; // an affine image: volume |det M| times the reference's
    for (const Vec3& xi : referenceNodes(element))
    {
      X.push_back(M * xi);
    }
    CHECK_NEAR(elementVolume(element, X.data()), std::abs(M.determinant()) * referenceVolume(element), 1e-13);
  }
}

TEST(UniformStrainPassesThePatchTest)
{
  // u = E x, lambda = F x on a distorted element: grad u = E, grad lambda = F at every point, so
  // the work is V a(E, F) with V the integrated volume (round-off only); a rigid motion (a
  // translation and a skew gradient: an infinitesimal rotation) does no work
  Sequence random{ 7 };
  Eigen::Matrix3d E, F, W;
  E << 1e-3, 2e-4, -3e-4, 5e-4, -2e-3, 1e-4, 0, 7e-4, 4e-4;
  F << -2e-4, 1e-3, 3e-4, 0, 5e-4, -6e-4, 2e-4, 1e-4, 1e-3;
  W << 0, 3e-3, -1e-3, -3e-3, 0, 2e-3, 1e-3, -2e-3, 0;
  const double l = Steel.lame(), m = Steel.shear();
  const double aEF = l * E.trace() * F.trace() + m * (E + E.transpose()).cwiseProduct(F).sum();
  for (SolidElement element : Elements)
  {
    const std::vector<Vec3> X = distorted(element, random);
    std::vector<Vec3> u, lambda, rigid;
    for (const Vec3& x : X)
    {
      u.push_back(E * x);
      lambda.push_back(F * x);
      rigid.push_back(W * x + Vec3(0.1, -0.2, 0.3));
    }
    const double V = elementVolume(element, X.data());
    CHECK(V > 0);
    const double work = elementWork(element, X.data(), u.data(), lambda.data(), Steel);
    CHECK_NEAR(work, V * aEF, 1e-10 * std::abs(V * aEF));
    CHECK_NEAR(elementWork(element, X.data(), rigid.data(), lambda.data(), Steel), 0.0, 1e-10 * std::abs(V * aEF));
  }
}

TEST(WorkAndVolumeDerivativesMatchCentralDifferences)
{
  // every node, every component: the exact derivative against central differences with h and
  // h / 2 (h = 1e-4 of an element of size ~1). Their truncation error is h^2 / 6 |W'''| (below
  // 1e-7 relative here) and their round-off eps |W| / h (1e-12 relative); the two differences
  // agree to a quarter of the first's truncation error, the exact one to both.
  Sequence random{ 11 };
  for (SolidElement element : Elements)
  {
    const int n = nodeCount(element);
    const std::vector<Vec3> X = distorted(element, random);
    std::vector<Vec3> u(n), lambda(n);
    for (int a = 0; a < n; ++a)
    {
      u[a] = 1e-3 * random.vector();
      lambda[a] = 1e-3 * random.vector();
    }
    std::vector<Vec3> dW(n, Vec3::Zero()), dV(n, Vec3::Zero());
    addElementWorkDerivative(element, X.data(), u.data(), lambda.data(), Steel, dW.data());
    addElementVolumeDerivative(element, X.data(), dV.data());
    double scaleW = 0, scaleV = 0;
    for (int a = 0; a < n; ++a)
    {
      scaleW = std::max(scaleW, dW[a].cwiseAbs().maxCoeff());
      scaleV = std::max(scaleV, dV[a].cwiseAbs().maxCoeff());
    }
    CHECK(scaleW > 0 && scaleV > 0);
    const auto central = [&](int a, int d, double h, bool volume) {
      std::vector<Vec3> plus = X, minus = X;
      plus[a][d] += h;
      minus[a][d] -= h;
      return volume ? (elementVolume(element, plus.data()) - elementVolume(element, minus.data())) / (2 * h)
                    : (elementWork(element, plus.data(), u.data(), lambda.data(), Steel) -
                        elementWork(element, minus.data(), u.data(), lambda.data(), Steel)) / (2 * h);
    };
    const double h = 1e-4;
    double worstW = 0, worstV = 0, worstAgreement = 0;
    for (int a = 0; a < n; ++a)
    {
      for (int d = 0; d < 3; ++d)
      {
        const double w1 = central(a, d, h, false), w2 = central(a, d, h / 2, false);
        const double v1 = central(a, d, h, true), v2 = central(a, d, h / 2, true);
        worstAgreement = std::max(worstAgreement, std::abs(w1 - w2) / scaleW);
        worstW = std::max(worstW, std::abs(dW[a][d] - w2) / scaleW);
        worstV = std::max({ worstV, std::abs(dV[a][d] - v2) / scaleV, std::abs(v1 - v2) / scaleV });
      }
    }
    std::printf("%s: exact against central differences (h/2) %.2e of the largest, h against h/2 %.2e (work); volume %.2e\n",
      nameOf(element).c_str(), worstW, worstAgreement, worstV);
    CHECK(worstAgreement < 1e-6);
    CHECK(worstW < 1e-6);
    CHECK(worstV < 1e-6);
  }
}

TEST(MeshSumsAreTheElementsSumsForAnyThreadCount)
{
  // the unit cube as 2 x 2 x 2 C3D8 elements, its centre node moved: the elements still tile the
  // cube, so the volume is 1 and does not change with the centre node (2 x 2 x 2 Gauss points
  // integrate a trilinear element's det J exactly: round-off only); the work's gradient at the
  // centre and at a corner against central differences as above; 1 and 2 threads the same bits
  PointList X;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        X.push_back(Vec3(i, j, k) / 2);
  const int centre = 13;
  X[centre] += Vec3(0.05, -0.03, 0.02);
  SolidMesh mesh;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
      {
        const auto at = [&](int di, int dj, int dk) { return (i + di) + 3 * (j + dj) + 9 * (k + dk); };
        const int nodes[8] = { at(0, 0, 0), at(1, 0, 0), at(1, 1, 0), at(0, 1, 0), at(0, 0, 1), at(1, 0, 1), at(1, 1, 1), at(0, 1, 1) };
        mesh.add(SolidElement::C3D8, nodes, (i + j + k) % 2);
      }
  const std::vector<IsotropicElastic> materials = { Steel, { 70000, 0.33 } };
  Sequence random{ 5 };
  PointList u(X.size()), lambda(X.size());
  for (std::size_t n = 0; n < X.size(); ++n)
  {
    u[n] = 1e-3 * random.vector();
    lambda[n] = 1e-3 * random.vector();
  }
  PointList dV, dW, dW1;
  CHECK_NEAR(meshVolume(mesh, X, { 1.0, 1.0 }, &dV), 1.0, 1e-14);
  CHECK_NEAR(dV[centre].norm(), 0.0, 1e-14);
  omp_set_num_threads(2);
  const double W = meshWork(mesh, X, u, lambda, materials, &dW);
  omp_set_num_threads(1);
  CHECK(meshWork(mesh, X, u, lambda, materials, &dW1) == W);
  CHECK(dW1 == dW);
  double scale = 0;
  for (const Vec3& g : dW)
  {
    scale = std::max(scale, g.cwiseAbs().maxCoeff());
  }
  for (int node : { centre, 0, 26 })
  {
    for (int d = 0; d < 3; ++d)
    {
      const double h = 5e-5;
      PointList plus = X, minus = X;
      plus[node][d] += h;
      minus[node][d] -= h;
      const double difference = (meshWork(mesh, plus, u, lambda, materials, nullptr) - meshWork(mesh, minus, u, lambda, materials, nullptr)) / (2 * h);
      CHECK_NEAR(dW[node][d], difference, 1e-6 * scale);
    }
  }
  bool refused = false; // a material index out of range
  try
  {
    meshWork(mesh, X, u, lambda, { Steel }, nullptr);
  }
  catch (const InvalidInputException&)
  {
    refused = true;
  }
  CHECK(refused);
}

TEST(DegenerateElementIsRefused)
{
  std::vector<Vec3> flat = { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0) }; // four points in a plane
  bool refused = false;
  try
  {
    elementVolume(SolidElement::C3D4, flat.data());
  }
  catch (const InvalidInputException&)
  {
    refused = true;
  }
  CHECK(refused);
}

TEST_MAIN
