#include "Structural/ShapeSensitivity.h"

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <algorithm>
#include <limits>
#include <string>

namespace mlsdeform
{
namespace
{
constexpr int MaxNodes = 20;

// At an integration point: |det J| w and grad N_a (J = sum_a X_a (dN_a/dxi)^T, grad N_a =
// J^-T dN_a/dxi). Throws for a degenerate element (det J = 0): no derivative exists there.
struct PointGeometry
{
  double weight; // w |det J|
  std::array<Vec3, MaxNodes> gradient;
};

PointGeometry pointGeometry(SolidElement element, const Vec3* X, const IntegrationPoint& point)
{
  const int n = nodeCount(element);
  std::array<double, MaxNodes> N;
  std::array<Vec3, MaxNodes> dN;
  shapeFunctions(element, point.xi, N.data(), dN.data());
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int a = 0; a < n; ++a)
  {
    J += X[a] * dN[a].transpose();
  }
  const double det = J.determinant();
  if (!(std::abs(det) > 0) || !std::isfinite(det))
  {
    throw InvalidInputException("a degenerate " + nameOf(element) + " element (det J = 0 at an integration point)");
  }
  PointGeometry g;
  g.weight = point.weight * std::abs(det);
  const Eigen::Matrix3d inverseTransposed = J.inverse().transpose();
  for (int a = 0; a < n; ++a)
  {
    g.gradient[a] = inverseTransposed * dN[a];
  }
  return g;
}

// grad v = sum_a v_a (x) grad N_a
Eigen::Matrix3d gradientOf(const PointGeometry& g, const Vec3* v, int n)
{
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
  for (int a = 0; a < n; ++a)
  {
    G += v[a] * g.gradient[a].transpose();
  }
  return G;
}

// a(G, H) = l tr G tr H + m (G + G^T) : H
double bilinear(const Eigen::Matrix3d& G, const Eigen::Matrix3d& H, const IsotropicElastic& material)
{
  return material.lame() * G.trace() * H.trace() + material.shear() * (G + G.transpose()).cwiseProduct(H).sum();
}
} // namespace

double elementWork(SolidElement element, const Vec3* X, const Vec3* u, const Vec3* lambda, const IsotropicElastic& material)
{
  const int n = nodeCount(element);
  double work = 0;
  for (const IntegrationPoint& point : integrationPoints(element))
  {
    const PointGeometry g = pointGeometry(element, X, point);
    work += g.weight * bilinear(gradientOf(g, u, n), gradientOf(g, lambda, n), material);
  }
  return work;
}

void addElementWorkDerivative(
  SolidElement element, const Vec3* X, const Vec3* u, const Vec3* lambda, const IsotropicElastic& material, Vec3* out)
{
  const int n = nodeCount(element);
  const double l = material.lame(), m = material.shear();
  for (const IntegrationPoint& point : integrationPoints(element))
  {
    const PointGeometry g = pointGeometry(element, X, point);
    const Eigen::Matrix3d G = gradientOf(g, u, n), H = gradientOf(g, lambda, n);
    // the header's (a I - A), weighted
    const Eigen::Matrix3d A =
      l * (H.trace() * G.transpose() + G.trace() * H.transpose()) + m * (G.transpose() * (H + H.transpose()) + H.transpose() * (G + G.transpose()));
    const Eigen::Matrix3d E = g.weight * (bilinear(G, H, material) * Eigen::Matrix3d::Identity() - A);
    for (int b = 0; b < n; ++b)
    {
      out[b] += E * g.gradient[b];
    }
  }
}

double elementVolume(SolidElement element, const Vec3* X)
{
  double volume = 0;
  for (const IntegrationPoint& point : integrationPoints(element))
  {
    volume += pointGeometry(element, X, point).weight;
  }
  return volume;
}

void addElementVolumeDerivative(SolidElement element, const Vec3* X, Vec3* out)
{
  const int n = nodeCount(element);
  for (const IntegrationPoint& point : integrationPoints(element))
  {
    const PointGeometry g = pointGeometry(element, X, point);
    for (int b = 0; b < n; ++b)
    {
      out[b] += g.weight * g.gradient[b];
    }
  }
}
void SolidMesh::add(SolidElement element, const int* elementNodes, int elementMaterial)
{
  type.push_back(element);
  nodes.insert(nodes.end(), elementNodes, elementNodes + nodeCount(element));
  start.push_back(static_cast<long>(nodes.size()));
  material.push_back(elementMaterial);
}

namespace
{
// sum_e value(e, X_e, out_e) over the mesh's elements with their contributions to the nodes'
// gradient out_e (one entry per node of the element, zeroed), the elements in parallel into one
// buffer, then summed node by node in element order (the same for any thread count); a failing
// element (the first by number) rethrown with its number.
template <typename Element>
double meshSum(const SolidMesh& mesh, std::size_t nodeCount, std::size_t materialCount, PointList* gradient, Element element)
{
  const long count = mesh.elements();
  if (static_cast<long>(mesh.start.size()) != count + 1 || static_cast<long>(mesh.material.size()) != count)
  {
    throw InvalidInputException("the solid mesh's arrays do not fit together");
  }
  for (long e = 0; e < count; ++e)
  {
    if (mesh.material[e] < 0 || static_cast<std::size_t>(mesh.material[e]) >= materialCount)
    {
      throw InvalidInputException("element " + std::to_string(e) + " has no material");
    }
  }
  if (std::any_of(mesh.nodes.begin(), mesh.nodes.end(), [&](int n) { return n < 0 || static_cast<std::size_t>(n) >= nodeCount; }))
  {
    throw InvalidInputException("a solid element refers to a node outside the " + std::to_string(nodeCount) + " given");
  }
  PointList contributions(gradient ? mesh.nodes.size() : 0, Vec3::Zero());
  std::vector<double> values(static_cast<std::size_t>(count), 0.0);
  long failed = count;
  std::string message;
#pragma omp parallel for schedule(dynamic, 1024)
  for (long e = 0; e < count; ++e)
  {
    try
    {
      values[e] = element(e, gradient ? contributions.data() + mesh.start[e] : nullptr);
    }
    catch (const std::exception& error)
    {
#pragma omp critical(MeshSumFailure)
      if (e < failed)
      {
        failed = e;
        message = error.what();
      }
    }
  }
  if (failed < count)
  {
    throw InvalidInputException("element " + std::to_string(failed) + ": " + message);
  }
  if (gradient)
  {
    gradient->assign(nodeCount, Vec3::Zero());
    for (std::size_t r = 0; r < mesh.nodes.size(); ++r)
    {
      (*gradient)[mesh.nodes[r]] += contributions[r];
    }
  }
  double sum = 0;
  for (double v : values)
  {
    sum += v;
  }
  return sum;
}

// The element's nodes' entries of a per-node array.
void gather(const SolidMesh& mesh, long e, const PointList& from, std::array<Vec3, MaxNodes>& to)
{
  for (long r = mesh.start[e]; r < mesh.start[e + 1]; ++r)
  {
    to[r - mesh.start[e]] = from[mesh.nodes[r]];
  }
}
} // namespace

double meshWork(const SolidMesh& mesh, const PointList& X, const PointList& u, const PointList& lambda,
  const std::vector<IsotropicElastic>& materials, PointList* gradient)
{
  if (u.size() != X.size() || lambda.size() != X.size())
  {
    throw InvalidInputException("the displacements and the adjoint need one vector per node");
  }
  return meshSum(mesh, X.size(), materials.size(), gradient, [&](long e, Vec3* out) {
    std::array<Vec3, MaxNodes> x, ue, le;
    gather(mesh, e, X, x);
    gather(mesh, e, u, ue);
    gather(mesh, e, lambda, le);
    const IsotropicElastic& material = materials[mesh.material[e]];
    if (out)
    {
      addElementWorkDerivative(mesh.type[e], x.data(), ue.data(), le.data(), material, out);
    }
    return elementWork(mesh.type[e], x.data(), ue.data(), le.data(), material);
  });
}

double meshVolume(const SolidMesh& mesh, const PointList& X, const std::vector<double>& weight, PointList* gradient)
{
  return meshSum(mesh, X.size(), weight.size(), gradient, [&](long e, Vec3* out) {
    const double w = weight[mesh.material[e]];
    if (w == 0)
    {
      return 0.0;
    }
    std::array<Vec3, MaxNodes> x;
    gather(mesh, e, X, x);
    if (out)
    {
      std::array<Vec3, MaxNodes> dV;
      std::fill(dV.begin(), dV.end(), Vec3::Zero());
      addElementVolumeDerivative(mesh.type[e], x.data(), dV.data());
      for (int b = 0; b < nodeCount(mesh.type[e]); ++b)
      {
        out[b] = w * dV[b];
      }
    }
    return w * elementVolume(mesh.type[e], x.data());
  });
}
} // namespace mlsdeform
