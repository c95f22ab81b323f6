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
  std::array<double, MaxNodes> value; // N_a
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
  g.value = N;
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

// v(xi) = sum_a N_a v_a
Vec3 valueOf(const PointGeometry& g, const Vec3* v, int n)
{
  Vec3 sum = Vec3::Zero();
  for (int a = 0; a < n; ++a)
  {
    sum += g.value[a] * v[a];
  }
  return sum;
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

double elementBodyWork(SolidElement element, const Vec3* X, const Vec3* v, const Vec3& b)
{
  double work = 0;
  for (const IntegrationPoint& point : integrationPoints(element))
  {
    const PointGeometry g = pointGeometry(element, X, point);
    work += g.weight * valueOf(g, v, nodeCount(element)).dot(b);
  }
  return work;
}

void addElementBodyWorkDerivative(SolidElement element, const Vec3* X, const Vec3* v, const Vec3& b, Vec3* out)
{
  const int n = nodeCount(element);
  for (const IntegrationPoint& point : integrationPoints(element))
  {
    const PointGeometry g = pointGeometry(element, X, point);
    const double density = g.weight * valueOf(g, v, n).dot(b);
    for (int c = 0; c < n; ++c)
    {
      out[c] += density * g.gradient[c];
    }
  }
}

namespace
{
// The stress and its deviator at a point: sigma = l tr G I + m (G + G^T).
Eigen::Matrix3d deviator(const Eigen::Matrix3d& G, const IsotropicElastic& material)
{
  const Eigen::Matrix3d sigma = material.lame() * G.trace() * Eigen::Matrix3d::Identity() + material.shear() * (G + G.transpose());
  return sigma - sigma.trace() / 3 * Eigen::Matrix3d::Identity();
}

double vonMisesOf(const Eigen::Matrix3d& s)
{
  return std::sqrt(1.5 * s.cwiseProduct(s).sum());
}
} // namespace

std::vector<double> elementVonMises(SolidElement element, const Vec3* X, const Vec3* u, const IsotropicElastic& material)
{
  std::vector<double> out;
  for (const IntegrationPoint& point : integrationPoints(element))
  {
    const PointGeometry g = pointGeometry(element, X, point);
    out.push_back(vonMisesOf(deviator(gradientOf(g, u, nodeCount(element)), material)));
  }
  return out;
}

void addElementVonMisesDerivatives(
  SolidElement element, const Vec3* X, const Vec3* u, const IsotropicElastic& material, const double* c, Vec3* dU, Vec3* dX)
{
  const int n = nodeCount(element);
  std::size_t k = 0;
  for (const IntegrationPoint& point : integrationPoints(element))
  {
    const PointGeometry g = pointGeometry(element, X, point);
    const Eigen::Matrix3d G = gradientOf(g, u, n), s = deviator(G, material);
    const double sigma = vonMisesOf(s), weight = c[k++];
    if (!(sigma > 0) || weight == 0)
    {
      continue;
    }
    const Eigen::Matrix3d dG = weight * 3 * material.shear() / sigma * s; // d(sigma_vm)/dG, weighted
    for (int a = 0; a < n; ++a)
    {
      if (dU)
      {
        dU[a] += dG * g.gradient[a];
      }
      if (dX)
      {
        dX[a] -= G.transpose() * dG * g.gradient[a];
      }
    }
  }
}

namespace
{
// At a face's integration point: the face's N_a, dN_a/d(xi, eta), t1 = dx/dxi, t2 = dx/deta and
// v there.
struct FacePoint
{
  std::array<double, 8> N;
  std::array<Vec3, 8> dN;
  Vec3 t1, t2, v;
};

FacePoint facePoint(const ElementFace& face, const Vec3* X, const Vec3* v, const IntegrationPoint& point)
{
  FacePoint f;
  faceShapeFunctions(face.nodes.size(), point.xi, f.N.data(), f.dN.data());
  f.t1 = f.t2 = f.v = Vec3::Zero();
  for (std::size_t k = 0; k < face.nodes.size(); ++k)
  {
    const int a = face.nodes[k];
    f.t1 += f.dN[k][0] * X[a];
    f.t2 += f.dN[k][1] * X[a];
    f.v += f.N[k] * v[a];
  }
  return f;
}
} // namespace

double facePressureWork(const ElementFace& face, const Vec3* X, const Vec3* v, double p)
{
  double work = 0;
  for (const IntegrationPoint& point : face.points)
  {
    const FacePoint f = facePoint(face, X, v, point);
    work -= p * point.weight * f.v.dot(f.t1.cross(f.t2));
  }
  return work;
}

void addFacePressureWorkDerivative(const ElementFace& face, const Vec3* X, const Vec3* v, double p, Vec3* out)
{
  for (const IntegrationPoint& point : face.points)
  {
    const FacePoint f = facePoint(face, X, v, point);
    const Vec3 along1 = f.t2.cross(f.v), along2 = f.v.cross(f.t1);
    for (std::size_t k = 0; k < face.nodes.size(); ++k)
    {
      out[face.nodes[k]] -= p * point.weight * (f.dN[k][0] * along1 + f.dN[k][1] * along2);
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
// The mesh's arrays fit together, its nodes and materials are among those given.
void requireConsistent(const SolidMesh& mesh, std::size_t nodeCount, std::size_t materialCount)
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
}

// body(k) for k = 0 .. count - 1 in parallel; a failure rethrown after the loop, the first by k,
// naming element elementOf(k) (an exception may not leave an OpenMP loop)
template <typename ElementOf, typename Body>
void forEachElement(long count, ElementOf elementOf, Body body)
{
  long failed = count;
  std::string message;
#pragma omp parallel for schedule(dynamic, 1024)
  for (long k = 0; k < count; ++k)
  {
    try
    {
      body(k);
    }
    catch (const std::exception& error)
    {
#pragma omp critical(ForEachElementFailure)
      if (k < failed)
      {
        failed = k;
        message = error.what();
      }
    }
  }
  if (failed < count)
  {
    throw InvalidInputException("element " + std::to_string(elementOf(failed)) + ": " + message);
  }
}

// sum_e value(e, X_e, out_e) over the mesh's elements with their contributions to the nodes'
// gradient out_e (one entry per node of the element, zeroed), the elements in parallel into one
// buffer, then summed node by node in element order (the same for any thread count); a failing
// element (the first by number) rethrown with its number.
template <typename Element>
double meshSum(const SolidMesh& mesh, std::size_t nodeCount, std::size_t materialCount, PointList* gradient, Element element)
{
  const long count = mesh.elements();
  requireConsistent(mesh, nodeCount, materialCount);
  PointList contributions(gradient ? mesh.nodes.size() : 0, Vec3::Zero());
  std::vector<double> values(static_cast<std::size_t>(count), 0.0);
  forEachElement(count, [](long e) { return e; },
    [&](long e) { values[e] = element(e, gradient ? contributions.data() + mesh.start[e] : nullptr); });
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

double meshBodyWork(const SolidMesh& mesh, const PointList& X, const PointList& v, const std::vector<Vec3>& force, PointList* gradient)
{
  if (v.size() != X.size() || static_cast<long>(force.size()) != mesh.elements())
  {
    throw InvalidInputException("the body loads need one vector per node and one force per element");
  }
  return meshSum(mesh, X.size(), std::numeric_limits<std::size_t>::max(), gradient, [&](long e, Vec3* out) {
    if (force[e].isZero(0))
    {
      return 0.0;
    }
    std::array<Vec3, MaxNodes> x, ve;
    gather(mesh, e, X, x);
    gather(mesh, e, v, ve);
    if (out)
    {
      addElementBodyWorkDerivative(mesh.type[e], x.data(), ve.data(), force[e], out);
    }
    return elementBodyWork(mesh.type[e], x.data(), ve.data(), force[e]);
  });
}

double meshStressAggregate(const SolidMesh& mesh, const PointList& X, const PointList& u, const std::vector<IsotropicElastic>& materials,
  const std::vector<long>& elements, double rho, double reference, PointList* dJdu, PointList* dJdX)
{
  if (!(rho > 0) || !(reference > 0) || !std::isfinite(rho) || !std::isfinite(reference))
  {
    throw InvalidInputException("the stress aggregate needs a positive, finite weight and reference stress");
  }
  if (u.size() != X.size())
  {
    throw InvalidInputException("the stress needs one displacement per node");
  }
  requireConsistent(mesh, X.size(), materials.size());
  const long count = static_cast<long>(elements.size());
  if (count == 0)
  {
    throw InvalidInputException("the stress aggregate's element set is empty");
  }
  for (long e : elements)
  {
    if (e < 0 || e >= mesh.elements())
    {
      throw InvalidInputException("the stress aggregate's element " + std::to_string(e) + " is not in the mesh");
    }
  }
  // the stresses, element by element (in parallel), then m and the sum in order
  std::vector<std::vector<double>> stress(static_cast<std::size_t>(count));
  forEachElement(count, [&](long k) { return elements[k]; }, [&](long k) {
    const long e = elements[k];
    std::array<Vec3, MaxNodes> x, ue;
    gather(mesh, e, X, x);
    gather(mesh, e, u, ue);
    stress[k] = elementVonMises(mesh.type[e], x.data(), ue.data(), materials[mesh.material[e]]);
  });
  double largest = 0;
  for (const auto& values : stress)
  {
    for (double v : values)
    {
      largest = std::max(largest, v);
    }
  }
  double sum = 0;
  for (auto& values : stress)
  {
    for (double& v : values)
    {
      v = std::exp(rho * (v - largest) / reference); // becomes the point's share before the division below
      sum += v;
    }
  }
  const double J = largest + reference / rho * std::log(sum);
  if (dJdu || dJdX)
  {
    // dJ/d(sigma_g) = exp(rho (sigma_g - m) / S) / sum: the points' weights c_g
    SolidMesh chosen;
    for (long e : elements)
    {
      chosen.add(mesh.type[e], mesh.nodes.data() + mesh.start[e], mesh.material[e]);
    }
    PointList contributionsU(chosen.nodes.size(), Vec3::Zero()), contributionsX(chosen.nodes.size(), Vec3::Zero());
#pragma omp parallel for schedule(dynamic, 1024)
    for (long k = 0; k < count; ++k)
    {
      const long e = elements[k];
      std::array<Vec3, MaxNodes> x, ue;
      gather(mesh, e, X, x);
      gather(mesh, e, u, ue);
      std::vector<double> c(stress[k]);
      for (double& w : c)
      {
        w /= sum;
      }
      addElementVonMisesDerivatives(mesh.type[e], x.data(), ue.data(), materials[mesh.material[e]], c.data(),
        contributionsU.data() + chosen.start[k], contributionsX.data() + chosen.start[k]);
    }
    for (PointList* gradient : { dJdu, dJdX })
    {
      if (gradient)
      {
        gradient->assign(X.size(), Vec3::Zero());
        const PointList& contributions = gradient == dJdu ? contributionsU : contributionsX;
        for (std::size_t r = 0; r < chosen.nodes.size(); ++r)
        {
          (*gradient)[chosen.nodes[r]] += contributions[r];
        }
      }
    }
  }
  return J;
}

double meshPressureWork(const SolidMesh& mesh, const PointList& X, const PointList& v, const std::vector<FacePressure>& faces,
  PointList* gradient)
{
  if (v.size() != X.size())
  {
    throw InvalidInputException("the pressure loads need one vector per node");
  }
  requireConsistent(mesh, X.size(), std::numeric_limits<std::size_t>::max());
  if (gradient)
  {
    gradient->assign(X.size(), Vec3::Zero());
  }
  double work = 0;
  ElementFace face;
  for (const FacePressure& load : faces)
  {
    if (load.element < 0 || load.element >= mesh.elements() || !elementFace(mesh.type[load.element], load.face, face))
    {
      throw InvalidInputException("a pressure on face " + std::to_string(load.face) + " of element " + std::to_string(load.element) +
        ", which it does not have");
    }
    const long e = load.element;
    std::array<Vec3, MaxNodes> x, ve, dW;
    gather(mesh, e, X, x);
    gather(mesh, e, v, ve);
    work += facePressureWork(face, x.data(), ve.data(), load.pressure);
    if (gradient)
    {
      std::fill(dW.begin(), dW.end(), Vec3::Zero());
      addFacePressureWorkDerivative(face, x.data(), ve.data(), load.pressure, dW.data());
      for (long r = mesh.start[e]; r < mesh.start[e + 1]; ++r)
      {
        (*gradient)[mesh.nodes[r]] += dW[r - mesh.start[e]];
      }
    }
  }
  return work;
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
