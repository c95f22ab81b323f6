// The solid elements (SolidElements.h) and their exact shape derivatives (ShapeSensitivity.h), for
// each of C3D4, C3D10, C3D8, C3D20, C3D20R, C3D6, C3D15 on distorted elements (curved edges where
// the element has midside nodes): the shape functions are a partition of unity, 1 at their own
// node and 0 at the others; the integration weights sum to the reference volume; a uniform strain
// passes the patch test (its work is V a(E, F) exactly) and a rigid motion does no work; and the
// derivatives of the work lambda^T K_e u, of the volume and of a body force's work agree with
// central differences.
#include "../TestHarness.h"
#include "Structural/ShapeSensitivity.h"

#include <Eigen/Dense>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
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

// The nodes in VTK's order, as the Mesh File reader gives a deck's elements: the same for
// tetrahedra and hexahedra; a deck's wedge turned over (its 1-2-3 the other way round).
std::vector<Vec3> inVtkOrder(SolidElement element, const std::vector<Vec3>& deck)
{
  if (element != SolidElement::C3D6 && element != SolidElement::C3D15)
  {
    return deck;
  }
  const int order[15] = { 0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13 };
  std::vector<Vec3> vtk;
  for (std::size_t i = 0; i < deck.size(); ++i)
  {
    vtk.push_back(deck[order[i]]);
  }
  return vtk;
}
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
    const Vec3 b(1, -2, 0.5); // a body force
    std::vector<Vec3> dW(n, Vec3::Zero()), dV(n, Vec3::Zero()), dB(n, Vec3::Zero());
    addElementWorkDerivative(element, X.data(), u.data(), lambda.data(), Steel, dW.data());
    addElementVolumeDerivative(element, X.data(), dV.data());
    addElementBodyWorkDerivative(element, X.data(), lambda.data(), b, dB.data());
    double scaleW = 0, scaleV = 0, scaleB = 0;
    for (int a = 0; a < n; ++a)
    {
      scaleW = std::max(scaleW, dW[a].cwiseAbs().maxCoeff());
      scaleV = std::max(scaleV, dV[a].cwiseAbs().maxCoeff());
      scaleB = std::max(scaleB, dB[a].cwiseAbs().maxCoeff());
    }
    CHECK(scaleW > 0 && scaleV > 0 && scaleB > 0);
    // the three functions of the nodes: the work, the volume, the body force's work on lambda
    const auto value = [&](const std::vector<Vec3>& x, int which) {
      return which == 0 ? elementWork(element, x.data(), u.data(), lambda.data(), Steel)
                        : which == 1 ? elementVolume(element, x.data()) : elementBodyWork(element, x.data(), lambda.data(), b);
    };
    const auto central = [&](int a, int d, double h, int which) {
      std::vector<Vec3> plus = X, minus = X;
      plus[a][d] += h;
      minus[a][d] -= h;
      return (value(plus, which) - value(minus, which)) / (2 * h);
    };
    const double h = 1e-4;
    double worstW = 0, worstV = 0, worstB = 0, worstAgreement = 0;
    for (int a = 0; a < n; ++a)
    {
      for (int d = 0; d < 3; ++d)
      {
        const double w1 = central(a, d, h, 0), w2 = central(a, d, h / 2, 0);
        const double v1 = central(a, d, h, 1), v2 = central(a, d, h / 2, 1);
        const double b1 = central(a, d, h, 2), b2 = central(a, d, h / 2, 2);
        worstAgreement = std::max(worstAgreement, std::abs(w1 - w2) / scaleW);
        worstW = std::max(worstW, std::abs(dW[a][d] - w2) / scaleW);
        worstV = std::max({ worstV, std::abs(dV[a][d] - v2) / scaleV, std::abs(v1 - v2) / scaleV });
        worstB = std::max({ worstB, std::abs(dB[a][d] - b2) / scaleB, std::abs(b1 - b2) / scaleB });
      }
    }
    std::printf("%s: exact against central differences (h/2) %.2e of the largest, h against h/2 %.2e (work); volume %.2e; "
                "body force %.2e\n",
      nameOf(element).c_str(), worstW, worstAgreement, worstV, worstB);
    CHECK(worstAgreement < 1e-6);
    CHECK(worstW < 1e-6);
    CHECK(worstV < 1e-6);
    CHECK(worstB < 1e-6);
    // a uniform lambda: the body force's work is V lambda . b
    const std::vector<Vec3> uniform(n, Vec3(0.3, 0.1, -0.2));
    CHECK_NEAR(elementBodyWork(element, X.data(), uniform.data(), b), elementVolume(element, X.data()) * uniform[0].dot(b),
      1e-13 * elementVolume(element, X.data()));
  }
}

TEST(VonMisesDerivativesMatchCentralDifferences)
{
  // sum_g c_g sigma_vm,g with positive weights: its derivatives along u (dU) and X at fixed u (dX)
  // against central differences, h and h/2 as above; a uniform strain gives every point the same
  // stress, that of the strain's sigma (a patch test)
  Sequence random{ 17 };
  for (SolidElement element : Elements)
  {
    const int n = nodeCount(element);
    const std::vector<Vec3> X = distorted(element, random);
    std::vector<Vec3> u(n);
    for (Vec3& x : u)
    {
      x = 1e-3 * random.vector();
    }
    std::vector<double> c;
    for (std::size_t g = 0; g < integrationPoints(element).size(); ++g)
    {
      c.push_back(0.5 + 0.5 * random.next());
    }
    const auto weighted = [&](const std::vector<Vec3>& x, const std::vector<Vec3>& v) {
      const std::vector<double> sigma = elementVonMises(element, x.data(), v.data(), Steel);
      double sum = 0;
      for (std::size_t g = 0; g < sigma.size(); ++g)
      {
        sum += c[g] * sigma[g];
      }
      return sum;
    };
    std::vector<Vec3> dU(n, Vec3::Zero()), dX(n, Vec3::Zero());
    addElementVonMisesDerivatives(element, X.data(), u.data(), Steel, c.data(), dU.data(), dX.data());
    double scaleU = 0, scaleX = 0;
    for (int a = 0; a < n; ++a)
    {
      scaleU = std::max(scaleU, dU[a].cwiseAbs().maxCoeff());
      scaleX = std::max(scaleX, dX[a].cwiseAbs().maxCoeff());
    }
    CHECK(scaleU > 0 && scaleX > 0);
    for (int a = 0; a < n; ++a)
    {
      for (int d = 0; d < 3; ++d)
      {
        const auto central = [&](bool alongU, double h) {
          std::vector<Vec3> xp = X, xm = X, up = u, um = u;
          (alongU ? up : xp)[a][d] += h;
          (alongU ? um : xm)[a][d] -= h;
          return (weighted(xp, up) - weighted(xm, um)) / (2 * h);
        };
        CHECK_NEAR(dU[a][d], central(true, 5e-8), 1e-6 * scaleU);
        CHECK_NEAR(central(true, 1e-7), central(true, 5e-8), 1e-6 * scaleU);
        CHECK_NEAR(dX[a][d], central(false, 5e-5), 1e-6 * scaleX);
        CHECK_NEAR(central(false, 1e-4), central(false, 5e-5), 1e-6 * scaleX);
      }
    }
    Eigen::Matrix3d E;
    E << 1e-3, 2e-4, -3e-4, 5e-4, -2e-3, 1e-4, 0, 7e-4, 4e-4;
    std::vector<Vec3> uniform;
    for (const Vec3& x : X)
    {
      uniform.push_back(E * x);
    }
    const Eigen::Matrix3d sigma = Steel.lame() * E.trace() * Eigen::Matrix3d::Identity() + Steel.shear() * (E + E.transpose());
    const Eigen::Matrix3d s = sigma - sigma.trace() / 3 * Eigen::Matrix3d::Identity();
    for (double v : elementVonMises(element, X.data(), uniform.data(), Steel))
    {
      CHECK_NEAR(v, std::sqrt(1.5 * s.cwiseProduct(s).sum()), 1e-9 * v);
    }
  }
}

TEST(PressureActsOnEveryFaceOutward)
{
  // On an affine image of each element (its nodes in VTK's order), the faces' area vectors (the work of a uniform v = e_d
  // divided by -p) point out of the element and sum to zero over its closed surface (each face
  // rule integrates a straight-sided face's normal exactly: round-off); on a distorted element,
  // the work's derivative against central differences (h, h/2, as above) for every face.
  Eigen::Matrix3d M;
  M << 1.3, 0.2, -0.1, 0.15, 0.9, 0.25, -0.05, 0.3, 1.1;
  Sequence random{ 13 };
  for (SolidElement element : Elements)
  {
    const int n = nodeCount(element);
    std::vector<Vec3> affine;
    for (const Vec3& xi : inVtkOrder(element, referenceNodes(element)))
    {
      affine.push_back(M * xi);
    }
    Vec3 centre = Vec3::Zero();
    for (const Vec3& x : affine)
    {
      centre += x / n;
    }
    Vec3 closed = Vec3::Zero();
    double size = 0;
    ElementFace face;
    int faces = 0;
    for (int f = 1; elementFace(element, f, face); ++f, ++faces)
    {
      Vec3 area, faceCentre = Vec3::Zero();
      for (int d = 0; d < 3; ++d)
      {
        const std::vector<Vec3> v(n, Vec3::Unit(d));
        area[d] = -facePressureWork(face, affine.data(), v.data(), 1.0);
      }
      for (int a : face.nodes)
      {
        faceCentre += affine[a] / static_cast<double>(face.nodes.size());
      }
      CHECK(area.dot(faceCentre - centre) > 0); // out of the element
      closed += area;
      size = std::max(size, area.norm());
    }
    CHECK(faces == (n == 4 || n == 10 ? 4 : n == 6 || n == 15 ? 5 : 6));
    CHECK_NEAR(closed.norm(), 0.0, 1e-13 * size);

    const std::vector<Vec3> X = inVtkOrder(element, distorted(element, random));
    std::vector<Vec3> v(n);
    for (Vec3& x : v)
    {
      x = random.vector();
    }
    for (int f = 1; elementFace(element, f, face); ++f)
    {
      std::vector<Vec3> dP(n, Vec3::Zero());
      addFacePressureWorkDerivative(face, X.data(), v.data(), 2.5, dP.data());
      double scale = 0;
      for (const Vec3& g : dP)
      {
        scale = std::max(scale, g.cwiseAbs().maxCoeff());
      }
      CHECK(scale > 0);
      for (int a = 0; a < n; ++a)
      {
        for (int d = 0; d < 3; ++d)
        {
          const auto central = [&](double h) {
            std::vector<Vec3> plus = X, minus = X;
            plus[a][d] += h;
            minus[a][d] -= h;
            return (facePressureWork(face, plus.data(), v.data(), 2.5) - facePressureWork(face, minus.data(), v.data(), 2.5)) / (2 * h);
          };
          const double d1 = central(1e-4), d2 = central(5e-5);
          CHECK_NEAR(d1, d2, 1e-6 * scale);
          CHECK_NEAR(dP[a][d], d2, 1e-6 * scale);
        }
      }
    }
    CHECK(!elementFace(element, 0, face) && !elementFace(element, 7, face));
  }
}

TEST(MeshSumsAreTheElementsSumsForAnyThreadCount)
{
  // the unit cube as 2 x 2 x 2 C3D8 elements, its centre node moved: the elements still tile the
  // cube, so the volume is 1 and does not change with the centre node (2 x 2 x 2 Gauss points
  // integrate a trilinear element's det J exactly: round-off only); the work's gradient at the
  // centre and at a corner against central differences as above; 1 and 2 threads the same bits;
  // the stresses' KS aggregate and its gradients
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
  // the stresses' KS aggregate over all elements: between the largest and the largest + S ln(N) /
  // rho, its gradients along u and X against central differences
  std::vector<long> all(mesh.elements());
  std::iota(all.begin(), all.end(), 0L);
  const double rho = 20, reference = 100;
  PointList dKu, dKx;
  const double K = meshStressAggregate(mesh, X, u, materials, all, rho, reference, &dKu, &dKx);
  double largest = 0;
  for (long e = 0; e < mesh.elements(); ++e)
  {
    std::vector<Vec3> x, ue;
    for (long r = mesh.start[e]; r < mesh.start[e + 1]; ++r)
    {
      x.push_back(X[mesh.nodes[r]]);
      ue.push_back(u[mesh.nodes[r]]);
    }
    for (double v : elementVonMises(mesh.type[e], x.data(), ue.data(), materials[mesh.material[e]]))
    {
      largest = std::max(largest, v);
    }
  }
  CHECK(K >= largest && K <= largest + reference * std::log(64.0) / rho);
  double scaleU = 0, scaleX = 0;
  for (std::size_t k = 0; k < X.size(); ++k)
  {
    scaleU = std::max(scaleU, dKu[k].cwiseAbs().maxCoeff());
    scaleX = std::max(scaleX, dKx[k].cwiseAbs().maxCoeff());
  }
  for (int node : { centre, 26 })
  {
    for (int d = 0; d < 3; ++d)
    {
      PointList up = u, um = u, xp = X, xm = X;
      up[node][d] += 5e-8;
      um[node][d] -= 5e-8;
      xp[node][d] += 5e-5;
      xm[node][d] -= 5e-5;
      CHECK_NEAR(dKu[node][d],
        (meshStressAggregate(mesh, X, up, materials, all, rho, reference, nullptr, nullptr) -
          meshStressAggregate(mesh, X, um, materials, all, rho, reference, nullptr, nullptr)) / 1e-7, 1e-5 * scaleU);
      CHECK_NEAR(dKx[node][d],
        (meshStressAggregate(mesh, xp, u, materials, all, rho, reference, nullptr, nullptr) -
          meshStressAggregate(mesh, xm, u, materials, all, rho, reference, nullptr, nullptr)) / 1e-4, 1e-5 * scaleX);
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
