#include "Solver/ConstraintProjections.h"

#include "Common/KdTree.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace mlsdeform
{
namespace
{
Vec3 mean(const PointList& x)
{
  Vec3 m = Vec3::Zero();
  for (const Vec3& p : x)
  {
    m += p;
  }
  return m / static_cast<double>(x.size());
}

// Orthonormal frame (u, v, n) with n the smallest principal direction of the points about c.
Eigen::Matrix3d principalFrame(const PointList& x, const Vec3& c)
{
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& p : x)
  {
    covariance += (p - c) * (p - c).transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Matrix3d frame;
  frame.col(0) = solver.eigenvectors().col(2);
  frame.col(1) = solver.eigenvectors().col(1);
  frame.col(2) = solver.eigenvectors().col(0);
  return frame;
}

using Mat3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;

Mat3X toMatrix(const PointList& x)
{
  Mat3X m(3, x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    m.col(i) = x[i];
  }
  return m;
}

PointList transformed(const Eigen::Matrix4d& T, const PointList& x)
{
  PointList out;
  out.reserve(x.size());
  for (const Vec3& p : x)
  {
    out.push_back(T.topLeftCorner<3, 3>() * p + T.topRightCorner<3, 1>());
  }
  return out;
}

// Eberly's cylinder error for axis direction W about the centered points y: returns G(W) and
// the center (relative to the mean) and squared radius.
double cylinderError(const PointList& y, const Vec3& W, Vec3& center, double& r2)
{
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - W * W.transpose();
  Eigen::Matrix3d S;
  S << 0, -W.z(), W.y(), W.z(), 0, -W.x(), -W.y(), W.x(), 0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vec3 B = Vec3::Zero();
  const double n = static_cast<double>(y.size());
  for (const Vec3& p : y)
  {
    const Vec3 q = P * p;
    A += q * q.transpose() / n;
    B += q.squaredNorm() * q / n;
  }
  const Eigen::Matrix3d Ahat = S * A * S.transpose();
  const double trace = (Ahat * A).trace();
  center = trace > 0 ? Vec3(Ahat * B / trace) : Vec3::Zero();
  r2 = 0;
  for (const Vec3& p : y)
  {
    r2 += (P * p - center).squaredNorm() / n;
  }
  double error = 0;
  for (const Vec3& p : y)
  {
    const double e = (P * p - center).squaredNorm() - r2;
    error += e * e / n;
  }
  return error;
}

Vec3 direction(double theta, double phi)
{
  return Vec3(std::cos(theta) * std::sin(phi), std::sin(theta) * std::sin(phi), std::cos(phi));
}
} // namespace

Plane fitPlane(const PointList& x)
{
  Plane plane;
  plane.point = mean(x);
  plane.normal = principalFrame(x, plane.point).col(2);
  for (int a = 0; a < 3; ++a)
  {
    if ((plane.normal - plane.normal[a] * Vec3::Unit(a)).norm() <= 1e-9)
    {
      plane.normal = Vec3::Unit(a);
    }
  }
  for (const Vec3& p : x)
  {
    plane.farthest = std::max(plane.farthest, std::abs(plane.normal.dot(p - plane.point)));
  }
  return plane;
}

PointList projectToPlane(const PointList& x)
{
  return x.size() < 3 ? x : projectTo(fitPlane(x), x);
}

PointList projectTo(const Plane& plane, const PointList& x)
{
  PointList out;
  out.reserve(x.size());
  for (const Vec3& p : x)
  {
    out.push_back(plane.project(p));
  }
  return out;
}

PointList projectToCircle(const PointList& x)
{
  if (x.size() < 3)
  {
    return x;
  }
  const Vec3 c = mean(x);
  const Eigen::Matrix3d frame = principalFrame(x, c);
  // In-plane coordinates and the algebraic circle fit: u^2 + v^2 + a u + b v + e = 0.
  std::vector<Eigen::Vector2d> q;
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (const Vec3& p : x)
  {
    const Eigen::Vector2d uv(frame.col(0).dot(p - c), frame.col(1).dot(p - c));
    q.push_back(uv);
    const Eigen::Vector3d row(uv.x(), uv.y(), 1.0);
    M += row * row.transpose();
    r -= uv.squaredNorm() * row;
  }
  const Eigen::Vector3d abe = M.ldlt().solve(r);
  Eigen::Vector2d center(-abe[0] / 2, -abe[1] / 2);
  double radius = std::sqrt(std::max(0.0, center.squaredNorm() - abe[2]));
  // Gauss-Newton on sum (|q - center| - radius)^2.
  for (int iteration = 0; iteration < 10; ++iteration)
  {
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    for (const Eigen::Vector2d& p : q)
    {
      const Eigen::Vector2d d = p - center;
      const double length = d.norm();
      if (length == 0)
      {
        continue;
      }
      const Eigen::Vector3d J(-d.x() / length, -d.y() / length, -1.0);
      JtJ += J * J.transpose();
      Jtr += J * (length - radius);
    }
    const Eigen::Vector3d step = JtJ.ldlt().solve(-Jtr);
    if (!step.allFinite())
    {
      break;
    }
    center += step.head<2>();
    radius += step[2];
    if (step.norm() < 1e-14 * (1 + radius))
    {
      break;
    }
  }
  PointList out;
  out.reserve(x.size());
  for (const Eigen::Vector2d& p : q)
  {
    const Eigen::Vector2d d = p - center;
    const Eigen::Vector2d onCircle = d.norm() > 0 ? Eigen::Vector2d(center + radius * d / d.norm()) : Eigen::Vector2d(center + Eigen::Vector2d(radius, 0));
    out.push_back(c + onCircle.x() * frame.col(0) + onCircle.y() * frame.col(1));
  }
  return out;
}

PointList projectToCylinder(const PointList& x, Vec3& axis)
{
  if (x.size() < 5)
  {
    return x;
  }
  const Vec3 c = mean(x);
  PointList y;
  y.reserve(x.size());
  for (const Vec3& p : x)
  {
    y.push_back(p - c);
  }
  Vec3 center;
  double r2 = 0;
  // Start: the given axis, or the best of a grid over the hemisphere.
  Vec3 best = axis;
  double bestError = std::numeric_limits<double>::infinity();
  double step = 0.05;
  if (!(best.squaredNorm() > 0))
  {
    const int thetas = 32, phis = 16;
    for (int i = 0; i < thetas; ++i)
    {
      for (int j = 0; j <= phis; ++j)
      {
        const Vec3 W = direction(2 * M_PI * i / thetas, 0.5 * M_PI * j / phis);
        const double error = cylinderError(y, W, center, r2);
        if (error < bestError)
        {
          bestError = error;
          best = W;
        }
      }
    }
    step = 0.5 * M_PI / phis;
  }
  best.normalize();
  bestError = cylinderError(y, best, center, r2);
  // Pattern search on the sphere around the best direction, halving the step.
  for (int refinement = 0; refinement < 200 && step > 1e-10; ++refinement)
  {
    const Vec3 u = best.unitOrthogonal(), v = best.cross(u);
    bool improved = false;
    for (const Vec3& move : { Vec3(u), Vec3(-u), Vec3(v), Vec3(-v) })
    {
      const Vec3 W = (best + step * move).normalized();
      const double error = cylinderError(y, W, center, r2);
      if (error < bestError)
      {
        bestError = error;
        best = W;
        improved = true;
      }
    }
    if (!improved)
    {
      step /= 2;
    }
  }
  axis = best;
  cylinderError(y, best, center, r2);
  const double radius = std::sqrt(r2);
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - best * best.transpose();
  PointList out;
  out.reserve(x.size());
  for (const Vec3& p : y)
  {
    const Vec3 radial = P * p - center;
    const double length = radial.norm();
    out.push_back(c + p - radial + (length > 0 ? Vec3(radius * radial / length) : Vec3(radius * best.unitOrthogonal())));
  }
  return out;
}

PointList projectToSimilarity(const PointList& rest, const PointList& x)
{
  return rest.size() < 2 ? x : transformed(Eigen::umeyama(toMatrix(rest), toMatrix(x), true), rest);
}

PointList projectToRigid(const PointList& rest, const PointList& x)
{
  return rest.size() < 2 ? x : transformed(Eigen::umeyama(toMatrix(rest), toMatrix(x), false), rest);
}

std::vector<int> mirrorPartners(const PointList& rest, const Plane& mirror, double tolerance)
{
  const KdTree tree(rest);
  std::vector<int> partner(rest.size(), -1);
  for (std::size_t i = 0; i < rest.size(); ++i)
  {
    const Vec3 image = rest[i] - 2 * mirror.normal.dot(rest[i] - mirror.point) * mirror.normal;
    const int j = tree.nearest(image);
    partner[i] = j >= 0 && (rest[j] - image).norm() <= tolerance ? j : -1;
  }
  return partner;
}

PointList projectToSymmetric(const PointList& rest, const PointList& x, const std::vector<int>& partner, const Plane& mirror)
{
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity() - 2 * mirror.normal * mirror.normal.transpose();
  PointList projected(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    const std::size_t j = static_cast<std::size_t>(partner[i]);
    projected[i] = rest[i] + 0.5 * ((x[i] - rest[i]) + R * (x[j] - rest[j]));
  }
  return projected;
}

Vec3 centroid(const PointList& x)
{
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : x)
  {
    sum += p;
  }
  return sum / static_cast<double>(x.size());
}

Vec3 distanceTranslation(const PointList& a, const PointList& b, const Vec3& axis, double distance)
{
  const Vec3 e = centroid(b) - centroid(a);
  const Vec3 direction = axis.squaredNorm() > 0 ? axis : e.normalized();
  const double error = e.dot(direction) - distance;
  // na |ta|^2 + nb |tb|^2 least with (tb - ta) . direction = -error: ta = error nb / (na + nb) direction
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  return error * nb / (na + nb) * direction;
}

PointList projectOutside(const ReferenceSurface& reference, const PointList& x, const std::vector<double>& side, double bound)
{
  PointList out = x;
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    const ReferenceSurface::Nearest q = reference.nearest(x[i]);
    const Vec3 away = x[i] - q.point;
    if (side[i] * away.dot(q.normal) < 0 || q.distance == 0)
    {
      out[i] = q.point + bound * side[i] * q.normal; // crossed: back to its side
    }
    else if (q.distance < bound)
    {
      out[i] = q.point + bound / q.distance * away;
    }
  }
  return out;
}
} // namespace mlsdeform
