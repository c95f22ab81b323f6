#include "Structural/ShapeSensitivity.h"

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <stdexcept>

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
    throw std::invalid_argument("a degenerate " + nameOf(element) + " element (det J = 0 at an integration point)");
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
} // namespace mlsdeform
