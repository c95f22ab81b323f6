#include "Primitives/Primitives.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace mlsdeform
{
namespace
{
// Two unit vectors orthogonal to a and to each other.
void tangentBasis(const Vec3& a, Vec3& e1, Vec3& e2)
{
  e1 = (std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(a).normalized();
  e2 = a.cross(e1);
}

// A point in a cone's coordinates: height h along the axis from the apex, distance rho from the
// axis in the unit direction radial, and its signed distance from the nappe. In the (h, rho)
// half plane the surface is the ray t (cos a, sin a), t >= 0: a point with along = h cos a +
// rho sin a >= 0 is closest to the ray's interior, any other to the apex.
struct ConePoint
{
  double h = 0, rho = 0, along = 0, distance = 0;
  Vec3 radial = Vec3::Zero();
  bool nearestApex() const { return along < 0; }
};

ConePoint conePoint(const Primitive& cone, const Vec3& x)
{
  ConePoint p;
  const Vec3 v = x - cone.center;
  p.h = v.dot(cone.axis);
  const Vec3 radial = v - p.h * cone.axis;
  p.rho = radial.norm();
  p.radial = p.rho > 0 ? Vec3(radial / p.rho) : Vec3(Vec3::Zero());
  p.along = p.h * cone.cosAngle + p.rho * cone.sinAngle;
  p.distance = p.nearestApex() ? std::hypot(p.h, p.rho) : p.rho * cone.cosAngle - p.h * cone.sinAngle;
  return p;
}

// Signed distance (positive outside) of x from the surface and, if asked, the unit normal at the
// closest surface point (one evaluation: the compatibility test needs both). For a cone, points
// whose closest surface point is the apex get their distance to it and the axis as normal.
double signedDistance(const Primitive& s, const Vec3& x, Vec3* normal = nullptr)
{
  switch (s.type)
  {
    case PrimitiveType::Plane:
      if (normal)
      {
        *normal = s.axis;
      }
      return s.axis.dot(x) - s.offset;
    case PrimitiveType::Sphere:
    case PrimitiveType::Cylinder:
    {
      const Vec3 v = x - s.center, radial = s.type == PrimitiveType::Sphere ? v : Vec3(v - v.dot(s.axis) * s.axis);
      const double r = radial.norm();
      if (normal)
      {
        *normal = r > 0 ? Vec3(radial / r) : Vec3(Vec3::UnitZ());
      }
      return r - s.radius;
    }
    case PrimitiveType::Cone:
    {
      const ConePoint p = conePoint(s, x);
      if (normal)
      {
        *normal = p.rho > 0 ? Vec3(s.cosAngle * p.radial - s.sinAngle * s.axis) : s.axis;
      }
      return p.distance;
    }
  }
  return 0;
}

// The primitive moved by the small parameter change theta around base (Levenberg-Marquardt
// works on these local coordinates): sphere (center, radius); cylinder (axis tilt in the
// tangent plane, axis point shift, radius); cone (apex, axis tilt, angle).
// At most six parameters (a cone's): fixed-capacity Eigen types, no allocation in the fit.
using Parameters = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
using ParameterMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

Primitive perturbed(const Primitive& base, const Parameters& theta)
{
  Primitive s = base;
  Vec3 e1, e2;
  tangentBasis(base.axis, e1, e2);
  switch (base.type)
  {
    case PrimitiveType::Sphere:
      s.center += theta.head<3>();
      s.radius += theta[3];
      break;
    case PrimitiveType::Cylinder:
      s.axis = (base.axis + theta[0] * e1 + theta[1] * e2).normalized();
      s.center += theta[2] * e1 + theta[3] * e2;
      s.radius += theta[4];
      break;
    case PrimitiveType::Cone:
      s.center += theta.head<3>();
      s.axis = (base.axis + theta[3] * e1 + theta[4] * e2).normalized();
      s.setAngle(base.angle + theta[5]);
      break;
    case PrimitiveType::Plane:
      break;
  }
  return s;
}

// The signed distance of y from base and its gradient with respect to perturbed's parameters
// theta at theta = 0 (the Jacobian row of Levenberg-Marquardt), with (e1, e2) = tangentBasis(axis).
// With v = y - center, h = v . axis, u the unit radial direction and rho the distance from the
// axis: a shift d of the center changes a sphere's or cylinder's distance by -u . d and a cone's
// by -normal . d; tilting the axis by e changes a cylinder's by -h (u . e) and a cone's by
// -(u . e)(h cos a + rho sin a); a radius by -1; a cone's angle by -(rho sin a + h cos a). Points
// nearest a cone's apex have the distance |v|, which only its position changes.
double signedDistanceGradient(const Primitive& s, const Vec3& y, const Vec3& e1, const Vec3& e2, double* gradient)
{
  const Vec3 v = y - s.center;
  Eigen::Map<Vec3> centerShift(gradient); // a sphere's and a cone's first three parameters
  switch (s.type)
  {
    case PrimitiveType::Sphere:
    {
      const double r = v.norm();
      const Vec3 u = r > 0 ? Vec3(v / r) : Vec3(Vec3::Zero());
      centerShift = -u;
      gradient[3] = -1;
      return r - s.radius;
    }
    case PrimitiveType::Cylinder:
    {
      const double h = v.dot(s.axis);
      const Vec3 w = v - h * s.axis;
      const double rho = w.norm();
      const Vec3 u = rho > 0 ? Vec3(w / rho) : Vec3(Vec3::Zero());
      gradient[0] = -h * u.dot(e1);
      gradient[1] = -h * u.dot(e2);
      gradient[2] = -u.dot(e1);
      gradient[3] = -u.dot(e2);
      gradient[4] = -1;
      return rho - s.radius;
    }
    case PrimitiveType::Cone:
    {
      const ConePoint p = conePoint(s, y);
      if (!p.nearestApex())
      {
        centerShift = -(s.cosAngle * p.radial - s.sinAngle * s.axis);
        gradient[3] = -p.radial.dot(e1) * p.along;
        gradient[4] = -p.radial.dot(e2) * p.along;
        gradient[5] = -p.along;
      }
      else
      {
        centerShift = p.distance > 0 ? Vec3(-v / p.distance) : Vec3(Vec3::Zero());
        gradient[3] = gradient[4] = gradient[5] = 0;
      }
      return p.distance;
    }
    case PrimitiveType::Plane:
      break;
  }
  return signedDistance(s, y);
}

// The weight of the a-th sample of a subset: 1 without weights.
double weightOf(const std::vector<double>* weights, std::size_t a)
{
  return weights ? (*weights)[a] : 1.0;
}

Primitive fitPlane(const Primitive& start, const PointList& points, const std::vector<int>& subset, const std::vector<double>* weights)
{
  Vec3 mean = Vec3::Zero();
  double total = 0;
  for (std::size_t a = 0; a < subset.size(); ++a)
  {
    mean += weightOf(weights, a) * points[subset[a]];
    total += weightOf(weights, a);
  }
  mean /= total;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t a = 0; a < subset.size(); ++a)
  {
    const Vec3 d = points[subset[a]] - mean;
    covariance += weightOf(weights, a) * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  Primitive plane;
  plane.type = PrimitiveType::Plane;
  // collinear points determine no plane: keep the start's normal
  const bool collinear = !(eigen.eigenvalues()[1] > 1e-12 * eigen.eigenvalues()[2]);
  plane.axis = collinear && start.type == PrimitiveType::Plane ? start.axis : Vec3(eigen.eigenvectors().col(0));
  plane.offset = plane.axis.dot(mean);
  return plane;
}

// Levenberg-Marquardt on the signed distances of the subset, each residual and Jacobian row
// (signedDistanceGradient) scaled by the square root of its weight, in coordinates centered at
// the subset's centroid and scaled by its spread (well conditioned).
Primitive fitGeometric(const Primitive& start, const PointList& points, const std::vector<int>& subset, const std::vector<double>* weights)
{
  const int m = parameterCount(start.type);
  const long n = static_cast<long>(subset.size());
  Vec3 mean = Vec3::Zero();
  for (int i : subset)
  {
    mean += points[i];
  }
  mean /= static_cast<double>(n);
  double spread = 0;
  for (int i : subset)
  {
    spread += (points[i] - mean).squaredNorm();
  }
  spread = std::sqrt(spread / n);
  if (!(spread > 0))
  {
    return start;
  }
  PointList y(n);
  for (long a = 0; a < n; ++a)
  {
    y[a] = (points[subset[a]] - mean) / spread;
  }
  Primitive current = start;
  current.center = (start.center - mean) / spread;
  current.radius = start.radius / spread;
  if (current.type == PrimitiveType::Cylinder)
  {
    // the axis point nearest to the centroid keeps the parameters small
    current.center -= current.center.dot(current.axis) * current.axis;
  }
  auto residuals = [&](const Primitive& s, Eigen::VectorXd& r) {
#pragma omp parallel for schedule(static) if (n >= ParallelSamples)
    for (long a = 0; a < n; ++a)
    {
      r[a] = std::sqrt(weightOf(weights, a)) * signedDistance(s, y[a]);
    }
  };
  // Levenberg-Marquardt; stops when a step gains less than 1e-10 of the cost, when the RMS
  // distance is below 1e-9 of the spread (settled far below any distance tolerance: exact data
  // would otherwise be refined to round-off), or when no damping finds a better fit
  Eigen::VectorXd r(n), rNext(n);
  residuals(current, r);
  double cost = r.squaredNorm(), lambda = 1e-3;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(n, m);
  for (int iteration = 0; iteration < 30; ++iteration)
  {
    Vec3 e1, e2;
    tangentBasis(current.axis, e1, e2);
#pragma omp parallel for schedule(static) if (n >= ParallelSamples)
    for (long a = 0; a < n; ++a)
    {
      signedDistanceGradient(current, y[a], e1, e2, J.row(a).data());
      J.row(a) *= std::sqrt(weightOf(weights, a));
    }
    const ParameterMatrix A = J.transpose() * J;
    const Parameters g = J.transpose() * r;
    double decrease = -1;
    for (int attempt = 0; attempt < 8 && decrease < 0; ++attempt)
    {
      ParameterMatrix damped = A;
      damped.diagonal() += lambda * A.diagonal() + Parameters::Constant(m, 1e-12);
      const Primitive next = perturbed(current, damped.ldlt().solve(-g));
      residuals(next, rNext);
      if (rNext.allFinite() && rNext.squaredNorm() < cost)
      {
        decrease = cost - rNext.squaredNorm();
        current = next;
        r.swap(rNext);
        cost = r.squaredNorm();
        lambda = std::max(lambda / 10, 1e-12);
      }
      else
      {
        lambda *= 10;
      }
    }
    if (decrease <= 1e-10 * (cost + decrease) || cost <= 1e-18 * static_cast<double>(n))
    {
      break;
    }
  }
  current.center = current.center * spread + mean;
  current.radius *= spread;
  return current;
}
}

int parameterCount(PrimitiveType type)
{
  return type == PrimitiveType::Sphere ? 4 : type == PrimitiveType::Cylinder ? 5 : type == PrimitiveType::Cone ? 6 : 3;
}

const char* primitiveTypeName(PrimitiveType type)
{
  switch (type)
  {
    case PrimitiveType::Plane:
      return "Plane";
    case PrimitiveType::Cylinder:
      return "Cylinder";
    case PrimitiveType::Sphere:
      return "Sphere";
    case PrimitiveType::Cone:
      return "Cone";
  }
  return "";
}

double Primitive::distance(const Vec3& x) const
{
  return std::abs(signedDistance(*this, x));
}

Vec3 Primitive::normalAt(const Vec3& x) const
{
  Vec3 normal;
  signedDistance(*this, x, &normal);
  return normal;
}

double Primitive::distance(const Vec3& x, Vec3& normal) const
{
  return std::abs(signedDistance(*this, x, &normal));
}

std::optional<Primitive> fitMinimal(PrimitiveType type, const Vec3 (&p)[3], const Vec3 (&n)[3], double epsilon, double cosAlpha)
{
  Primitive s;
  s.type = type;
  switch (type)
  {
    case PrimitiveType::Plane:
    {
      const Vec3 normal = (p[1] - p[0]).cross(p[2] - p[0]);
      if (!(normal.norm() > 0))
      {
        return std::nullopt;
      }
      s.axis = normal.normalized();
      s.offset = s.axis.dot(p[0]);
      break;
    }
    case PrimitiveType::Sphere:
    {
      // the midpoint of the shortest segment between the normal lines p_i + t n_i (i = 0, 1)
      const double b = n[0].dot(n[1]), denominator = 1 - b * b;
      if (!(denominator > 1e-12))
      {
        return std::nullopt;
      }
      const Vec3 w = p[0] - p[1];
      const double d = n[0].dot(w), e = n[1].dot(w);
      const double t = (b * e - d) / denominator, u = (e - b * d) / denominator;
      s.center = 0.5 * (p[0] + t * n[0] + p[1] + u * n[1]);
      s.radius = ((p[0] - s.center).norm() + (p[1] - s.center).norm()) / 2;
      break;
    }
    case PrimitiveType::Cylinder:
    {
      // axis n_0 x n_1; the center where the normal lines meet in the plane normal to it
      const Vec3 axis = n[0].cross(n[1]);
      if (!(axis.norm() > 1e-6))
      {
        return std::nullopt;
      }
      s.axis = axis.normalized();
      auto flat = [&](const Vec3& v) { return Vec3(v - v.dot(s.axis) * s.axis); };
      const Vec3 q0 = flat(p[0]), q1 = flat(p[1]), m0 = flat(n[0]).normalized(), m1 = flat(n[1]).normalized();
      const double b = m0.dot(m1), denominator = 1 - b * b;
      if (!(denominator > 1e-12))
      {
        return std::nullopt;
      }
      const Vec3 w = q0 - q1;
      const double d = m0.dot(w), e = m1.dot(w);
      const double t = (b * e - d) / denominator, u = (e - b * d) / denominator;
      s.center = 0.5 * (q0 + t * m0 + q1 + u * m1);
      s.radius = ((q0 - s.center).norm() + (q1 - s.center).norm()) / 2;
      break;
    }
    case PrimitiveType::Cone:
    {
      // apex: the common point of the three tangent planes n_i . x = n_i . p_i
      Eigen::Matrix3d A;
      Vec3 rhs;
      for (int i = 0; i < 3; ++i)
      {
        A.row(i) = n[i].transpose();
        rhs[i] = n[i].dot(p[i]);
      }
      if (!(std::abs(A.determinant()) > 1e-6))
      {
        return std::nullopt;
      }
      s.center = A.partialPivLu().solve(rhs);
      // the axis makes the same angle with the three directions from the apex
      Vec3 u[3];
      for (int i = 0; i < 3; ++i)
      {
        const Vec3 v = p[i] - s.center;
        if (!(v.norm() > 0))
        {
          return std::nullopt;
        }
        u[i] = v.normalized();
      }
      const Vec3 axis = (u[1] - u[0]).cross(u[2] - u[0]);
      if (!(axis.norm() > 1e-12))
      {
        return std::nullopt;
      }
      s.axis = axis.normalized();
      if (s.axis.dot(u[0]) < 0)
      {
        s.axis = -s.axis;
      }
      s.setAngle((std::acos(std::clamp(s.axis.dot(u[0]), -1.0, 1.0)) + std::acos(std::clamp(s.axis.dot(u[1]), -1.0, 1.0)) +
                   std::acos(std::clamp(s.axis.dot(u[2]), -1.0, 1.0))) / 3);
      if (s.angle < MinimumConeAngle || s.angle > M_PI / 2 - MinimumConeAngle)
      {
        return std::nullopt;
      }
      break;
    }
  }
  const bool finite = s.axis.allFinite() && s.center.allFinite() && std::isfinite(s.radius) && std::isfinite(s.offset);
  if (!finite || ((type == PrimitiveType::Sphere || type == PrimitiveType::Cylinder) && !(s.radius > 0)))
  {
    return std::nullopt;
  }
  for (int i = 0; i < 3; ++i)
  {
    if (!s.compatible(p[i], n[i], epsilon, cosAlpha))
    {
      return std::nullopt;
    }
  }
  return s;
}

DistanceStatistics distanceStatistics(const Primitive& shape, const PointList& points, const std::vector<int>& subset)
{
  DistanceStatistics statistics;
  double squared = 0;
  for (int i : subset)
  {
    const double d = shape.distance(points[i]);
    squared += d * d;
    statistics.max = std::max(statistics.max, d);
  }
  statistics.rms = subset.empty() ? 0 : std::sqrt(squared / static_cast<double>(subset.size()));
  return statistics;
}

Primitive fitLeastSquares(const Primitive& start, const PointList& points, const std::vector<int>& subset, const std::vector<double>* weights)
{
  // three points determine a plane; Levenberg-Marquardt needs more samples than parameters
  const int needed = start.type == PrimitiveType::Plane ? 3 : parameterCount(start.type) + 1;
  if (static_cast<int>(subset.size()) < needed)
  {
    return start;
  }
  return start.type == PrimitiveType::Plane ? fitPlane(start, points, subset, weights) : fitGeometric(start, points, subset, weights);
}

Primitive fitMinimax(const Primitive& start, const PointList& points, const std::vector<int>& subset, double enough, int iterations)
{
  // Lawson's algorithm: weighted least squares whose weights grow with the distances,
  // w <- w (|r| + tiny) / mean(w (|r| + tiny)); its weights converge to those of the minimax
  // (Chebyshev) fit. The tiny term keeps a sample at distance 0 from losing its weight for good.
  const std::size_t n = subset.size();
  std::vector<double> weights(n, 1.0), distance(n);
  Primitive best = start, current = start;
  double bestLargest = distanceStatistics(start, points, subset).max;
  for (int k = 0; k < iterations && n > 0 && !(bestLargest < enough); ++k)
  {
    current = fitLeastSquares(current, points, subset, &weights);
    double largest = 0, total = 0;
    for (std::size_t a = 0; a < n; ++a)
    {
      distance[a] = current.distance(points[subset[a]]);
      largest = std::max(largest, distance[a]);
    }
    if (!std::isfinite(largest))
    {
      break;
    }
    if (largest < bestLargest)
    {
      best = current;
      bestLargest = largest;
    }
    const double tiny = 1e-6 * largest;
    for (std::size_t a = 0; a < n; ++a)
    {
      weights[a] *= distance[a] + tiny;
      total += weights[a];
    }
    if (!(total > 0))
    {
      break;
    }
    for (double& w : weights)
    {
      w *= static_cast<double>(n) / total;
    }
  }
  return best;
}
} // namespace mlsdeform
