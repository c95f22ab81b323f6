#include "MLSBasis.h"

#include <Eigen/Dense>

#include <cmath>

namespace mlsdeform
{
namespace
{
using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;

// Singular values below this fraction of the largest are treated as zero in M^+.
constexpr double PseudoInverseTolerance = 1e-8;

// M^+ = V Sigma^+ U^T from the SVD M = U Sigma V^T [33, 34]. In the basis shifted to the weighted
// centroid, M = [W 0; 0 S] is block diagonal and symmetric positive semi-definite, so its SVD is
// the eigen-decomposition of the blocks: M^+ = [1/W 0; 0 S^+] with S^+ from the 3 x 3 S.
Mat4 pseudoInverse(const Mat4& M)
{
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(M.bottomRightCorner<3, 3>());
  const Eigen::Vector3d& s = eigen.eigenvalues();
  const double largest = std::max(M(0, 0), s.cwiseAbs().maxCoeff());
  Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
  {
    if (s[i] > PseudoInverseTolerance * largest)
    {
      inverse[i] = 1.0 / s[i];
    }
  }
  Mat4 Minv = Mat4::Zero();
  Minv(0, 0) = M(0, 0) > PseudoInverseTolerance * largest ? 1.0 / M(0, 0) : 0.0;
  Minv.bottomRightCorner<3, 3>() = eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
  return Minv;
}
}

MLSBasis::MLSBasis(const PointList& centers, const std::vector<double>& supportRadii)
  : Centers(centers)
  , Radii(supportRadii)
  , Supports(centers)
{
  requireSupportRadii(centers, supportRadii, "MLS");
  Supports.setRadii(supportRadii);
}

double MLSBasis::weight(double r, double sigma)
{
  return r < sigma ? 0.5 * std::cos(M_PI * r / sigma) + 0.5 : 0.0;
}

void MLSBasis::evaluate(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const
{
  Supports.containing(x, out.index);
  const std::size_t n = out.index.size();
  out.value.resize(n);
  out.gradient.resize(withDerivatives ? n : 0);
  out.laplacian.resize(withDerivatives ? n : 0);
  if (n == 0)
  {
    return;
  }

  // Weights w_j and, for derivatives, their gradient and the diagonal of their Hessian.
  std::vector<double> w(n);
  std::vector<Vec3> dw(withDerivatives ? n : 0), ddw(withDerivatives ? n : 0);
  double W = 0;
  Vec3 centroid = Vec3::Zero();
  double scale = 0;
  for (std::size_t a = 0; a < n; ++a)
  {
    const int j = out.index[a];
    const double sigma = Radii[j];
    const Vec3 u = x - Centers[j];
    const double r = u.norm();
    const double t = M_PI * r / sigma;
    w[a] = 0.5 * std::cos(t) + 0.5;
    W += w[a];
    centroid += w[a] * Centers[j];
    scale = std::max(scale, sigma);
    if (withDerivatives)
    {
      // w'(r) = -pi/(2 sigma) sin(t), w''(r) = -pi^2/(2 sigma^2) cos(t); w'(r)/r -> w''(0) at r = 0
      const double d2 = -M_PI * M_PI / (2 * sigma * sigma);
      const double dr = r > 1e-12 * sigma ? -M_PI / (2 * sigma) * std::sin(t) / r : d2;
      const double ddr = d2 * std::cos(t);
      dw[a] = dr * u;
      for (int d = 0; d < 3; ++d)
      {
        const double c2 = r > 1e-12 * sigma ? u[d] * u[d] / (r * r) : 0.0;
        ddw[a][d] = ddr * c2 + dr * (1 - c2);
      }
    }
  }
  if (!(W > 0))
  {
    out.index.clear();
    out.value.clear();
    out.gradient.clear();
    out.laplacian.clear();
    return;
  }
  // The basis is shifted to the weighted centroid s and scaled by the largest support radius h,
  // p(y) = (1, (y - s)/h): MLS is invariant to this change of basis, it keeps M well scaled and,
  // with the pseudo-inverse, keeps the partition of unity exact for coplanar samples.
  centroid /= W;
  auto basis = [&](const Vec3& y) {
    Vec4 p;
    p << 1.0, (y - centroid) / scale;
    return p;
  };
  std::vector<Vec4> p(n);
  Mat4 M = Mat4::Zero();
  for (std::size_t a = 0; a < n; ++a)
  {
    p[a] = basis(Centers[out.index[a]]);
    M.noalias() += w[a] * p[a] * p[a].transpose();
  }
  const Mat4 Minv = pseudoInverse(M);
  const Vec4 b = Minv * basis(x); // phi_j = w_j p_j^T b
  for (std::size_t a = 0; a < n; ++a)
  {
    out.value[a] = w[a] * p[a].dot(b);
  }
  if (!withDerivatives)
  {
    return;
  }
  // From M b = p: db = M^+(dp - dM b) and d2b = M^+(-d2M b - 2 dM db) per axis (d2p = 0).
  Vec4 db[3], ddb[3];
  for (int d = 0; d < 3; ++d)
  {
    Mat4 dM = Mat4::Zero(), ddM = Mat4::Zero();
    for (std::size_t a = 0; a < n; ++a)
    {
      const Mat4 ppT = p[a] * p[a].transpose();
      dM.noalias() += dw[a][d] * ppT;
      ddM.noalias() += ddw[a][d] * ppT;
    }
    Vec4 dp = Vec4::Zero();
    dp[1 + d] = 1.0 / scale;
    db[d] = Minv * (dp - dM * b);
    ddb[d] = Minv * (-ddM * b - 2.0 * dM * db[d]);
  }
  for (std::size_t a = 0; a < n; ++a)
  {
    const double pb = p[a].dot(b);
    double laplacian = 0;
    for (int d = 0; d < 3; ++d)
    {
      const double pdb = p[a].dot(db[d]);
      out.gradient[a][d] = pdb * w[a] + pb * dw[a][d];
      laplacian += p[a].dot(ddb[d]) * w[a] + 2.0 * pdb * dw[a][d] + pb * ddw[a][d];
    }
    out.laplacian[a] = laplacian;
  }
}
} // namespace mlsdeform
