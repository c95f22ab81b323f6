#include "MLSBasis.h"

#include <Eigen/Dense>

#include <algorithm>
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

void cosSinPi(double s, double& cosine, double& sine)
{
  // u = s, 1/2 - s, s - 1/2 or 1 - s: each difference is exact (Sterbenz), and
  // cos(pi s), sin(pi s) = (C, S), (S, C), (-S, C), (-C, S) of pi u
  const bool upper = s > 0.5;
  const double half = upper ? s - 0.5 : s; // in [0, 1/2]; cos(pi s) = -sin(pi half) above 1/2
  const bool swap = half > 0.25;
  const double u = swap ? 0.5 - half : half;
  const double t = M_PI * u, t2 = t * t;
  const double C = 1 + t2 * (-1.0 / 2 + t2 * (1.0 / 24 + t2 * (-1.0 / 720 + t2 * (1.0 / 40320 + t2 * (-1.0 / 3628800 +
    t2 * (1.0 / 479001600 + t2 * (-1.0 / 87178291200 + t2 * (1.0 / 20922789888000))))))));
  const double S = t * (1 + t2 * (-1.0 / 6 + t2 * (1.0 / 120 + t2 * (-1.0 / 5040 + t2 * (1.0 / 362880 + t2 * (-1.0 / 39916800 +
    t2 * (1.0 / 6227020800 + t2 * (-1.0 / 1307674368000 + t2 * (1.0 / 355687428096000)))))))));
  // on [0, 1/2]: cos(pi half), sin(pi half) = (C, S) below 1/4, (S, C) above
  const double c = swap ? S : C, sn = swap ? C : S;
  cosine = upper ? -sn : c;
  sine = upper ? c : sn;
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
  if (!(r < sigma))
  {
    return 0.0;
  }
  double cosine, sine;
  cosSinPi(r / sigma, cosine, sine);
  return 0.5 * cosine + 0.5;
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
    double cosine, sine; // of t = pi r / sigma
    cosSinPi(std::min(r / sigma, 1.0), cosine, sine);
    w[a] = 0.5 * cosine + 0.5;
    W += w[a];
    centroid += w[a] * Centers[j];
    scale = std::max(scale, sigma);
    if (withDerivatives)
    {
      // w'(r) = -pi/(2 sigma) sin(t), w''(r) = -pi^2/(2 sigma^2) cos(t); w'(r)/r -> w''(0) at r = 0
      const double d2 = -M_PI * M_PI / (2 * sigma * sigma);
      const double dr = r > 1e-12 * sigma ? -M_PI / (2 * sigma) * sine / r : d2;
      const double ddr = d2 * cosine;
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
