#include "Basis/MLSBasis.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace mlsdeform
{
namespace
{
using Vec4 = Eigen::Vector4d;
using Mat4 = Eigen::Matrix4d;

// a[0] + a[1] y + ... + a[10] y^10 by Estrin's scheme: a third of Horner's chain of dependent
// operations, which bounded the weight loops.
double degree10(const double (&a)[11], double y)
{
  const double y2 = y * y, y4 = y2 * y2, y8 = y4 * y4;
  const double low = (a[0] + a[1] * y) + (a[2] + a[3] * y) * y2;
  const double high = (a[4] + a[5] * y) + (a[6] + a[7] * y) * y2;
  return low + high * y4 + ((a[8] + a[9] * y) + a[10] * y2) * y8;
}

// Singular values below this fraction of the largest are treated as zero in M^+.
constexpr double PseudoInverseTolerance = 1e-8;

// M^+ = V Sigma^+ U^T from the SVD M = U Sigma V^T [33, 34]. In the basis shifted to the weighted
// centroid, M = [W 0; 0 S] is block diagonal and symmetric positive semi-definite, so its SVD is
// the eigen-decomposition of the blocks: M^+ = [1/W 0; 0 S^+] with S^+ from the 3 x 3 S.
Mat4 pseudoInverse(double W, const Eigen::Matrix3d& S)
{
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(S);
  const Eigen::Vector3d& s = eigen.eigenvalues();
  const double largest = std::max(W, s.cwiseAbs().maxCoeff());
  Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
  {
    if (s[i] > PseudoInverseTolerance * largest)
    {
      inverse[i] = 1.0 / s[i];
    }
  }
  Mat4 Minv = Mat4::Zero();
  Minv(0, 0) = W > PseudoInverseTolerance * largest ? 1.0 / W : 0.0;
  Minv.bottomRightCorner<3, 3>() = eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
  return Minv;
}
}

namespace
{
// Taylor coefficients in u of cos(pi/2 sqrt(u)) and of sin(pi/2 sqrt(u)) / (pi/2 sqrt(u)),
// (-pi^2/4)^k / (2k)! and (-pi^2/4)^k / (2k + 1)!, k = 0 .. 10.
constexpr double Q = -M_PI * M_PI / 4;
constexpr double HalfCosine[11] = { 1, Q / 2, Q * Q / 24, Q * Q * Q / 720, Q * Q * Q * Q / 40320, Q * Q * Q * Q * Q / 3628800,
  Q * Q * Q * Q * Q * Q / 479001600, Q * Q * Q * Q * Q * Q * Q / 87178291200.0, Q * Q * Q * Q * Q * Q * Q * Q / 20922789888000.0,
  Q * Q * Q * Q * Q * Q * Q * Q * Q / 6402373705728000.0, Q * Q * Q * Q * Q * Q * Q * Q * Q * Q / 2432902008176640000.0 };
constexpr double HalfSinc[11] = { 1, Q / 6, Q * Q / 120, Q * Q * Q / 5040, Q * Q * Q * Q / 362880, Q * Q * Q * Q * Q / 39916800,
  Q * Q * Q * Q * Q * Q / 6227020800.0, Q * Q * Q * Q * Q * Q * Q / 1307674368000.0, Q * Q * Q * Q * Q * Q * Q * Q / 355687428096000.0,
  Q * Q * Q * Q * Q * Q * Q * Q * Q / 121645100408832000.0, Q * Q * Q * Q * Q * Q * Q * Q * Q * Q / 51090942171709440000.0 };

// Local to this file (so that it is inlined into the weight loops; the exported halfAngle cannot
// be, as a shared library's symbol may be interposed).
double halfCosine(double u)
{
  return degree10(HalfCosine, u);
}
}

HalfAngle halfAngle(double u)
{
  return { halfCosine(u), degree10(HalfSinc, u) };
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
  const double c = halfCosine((r / sigma) * (r / sigma));
  return c * c;
}

void MLSBasis::evaluate(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const
{
  Supports.containing(x, out.index);
  out.value.resize(out.index.size());
  for (std::size_t a = 0; a < out.index.size(); ++a)
  {
    out.value[a] = (Centers[out.index[a]] - x).squaredNorm();
  }
  evaluateSupports(x, out, withDerivatives);
}

bool MLSBasis::candidatesInBox(const Vec3& lower, const Vec3& upper, std::vector<int>& candidates) const
{
  Supports.meetingBox(lower, upper, candidates);
  return true;
}

void MLSBasis::narrowCandidates(const Vec3& lower, const Vec3& upper, const std::vector<int>& candidates, std::vector<int>& narrowed) const
{
  Supports.meetingBoxAmong(lower, upper, candidates, narrowed);
}

void MLSBasis::evaluateAmong(const Vec3& x, const std::vector<int>& candidates, ShapeFunctionValues& out, bool withDerivatives) const
{
  // Every candidate is written and the count advances only for those whose support holds x: a
  // third of a box's candidates do, in no predictable pattern, and a branch on the test
  // mispredicted so often that it took half of Phi's time.
  out.index.resize(candidates.size());
  out.value.resize(candidates.size());
  std::size_t count = 0;
  for (int j : candidates)
  {
    const double squared = (Centers[j] - x).squaredNorm();
    out.index[count] = j;
    out.value[count] = squared;
    count += squared < Radii[j] * Radii[j]; // the test of KdTree::containing
  }
  out.index.resize(count);
  out.value.resize(count);
  evaluateSupports(x, out, withDerivatives);
}

void MLSBasis::evaluateSupports(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const
{
  const std::size_t n = out.index.size();
  out.gradient.resize(withDerivatives ? n : 0);
  out.laplacian.resize(withDerivatives ? n : 0);
  if (n == 0)
  {
    return;
  }

  // Weights w_j (in out.value, in place of the squared distances, until phi_j replaces them) and,
  // for derivatives, their gradient and the diagonal of their Hessian.
  std::vector<double>& w = out.value;
  std::vector<Vec3> dw(withDerivatives ? n : 0), ddw(withDerivatives ? n : 0);
  double W = 0;
  Vec3 centroid = Vec3::Zero();
  double scale = 0;
  for (std::size_t a = 0; a < n; ++a)
  {
    const int j = out.index[a];
    const double sigma = Radii[j];
    const double r2 = out.value[a]; // replaced by w_j below
    const double u = std::min(r2 / (sigma * sigma), 1.0); // (r / sigma)^2
    // w = 1/2 cos t + 1/2 = c^2 with c = cos(t/2), t = pi r / sigma: a polynomial in u, no square
    // root and no argument reduction
    const double c = halfCosine(u);
    w[a] = c * c;
    W += w[a];
    centroid += w[a] * Centers[j];
    scale = std::max(scale, sigma);
    if (withDerivatives)
    {
      // w'(r) = -pi/(2 sigma) sin t = -pi^2/(2 sigma^2) c sinc(t/2) r, w''(r) = -pi^2/(2 sigma^2) cos t
      // with sin t = 2 sin(t/2) c, cos t = 1 - 2 sin^2(t/2); so w'(r)/r needs no division by r
      const double sinc = degree10(HalfSinc, u);
      const double d2 = -M_PI * M_PI / (2 * sigma * sigma);
      const double dr = d2 * c * sinc; // w'(r) / r
      const double ddr = d2 * (1 + Q * 2 * u * sinc * sinc);
      const Vec3 u3 = x - Centers[j];
      dw[a] = dr * u3;
      for (int d = 0; d < 3; ++d)
      {
        const double c2 = r2 > 1e-24 * sigma * sigma ? u3[d] * u3[d] / r2 : 0.0;
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
  // p(y) = (1, q(y)); M's blocks are W = sum_j w_j and S = sum_j w_j q_j q_j^T.
  const double inverseScale = 1.0 / scale;
  const auto q = [&](std::size_t a) -> Vec3 { return (Centers[out.index[a]] - centroid) * inverseScale; };
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (std::size_t a = 0; a < n; ++a)
  {
    const Vec3 qa = q(a);
    S.noalias() += w[a] * qa * qa.transpose();
  }
  const Mat4 Minv = pseudoInverse(W, S);
  Vec4 px;
  px << 1.0, (x - centroid) * inverseScale;
  const Vec4 b = Minv * px; // phi_j = w_j p_j^T b
  const double b0 = b[0];
  const Vec3 bq = b.tail<3>();
  if (!withDerivatives)
  {
    for (std::size_t a = 0; a < n; ++a)
    {
      out.value[a] = w[a] * (b0 + q(a).dot(bq));
    }
    return;
  }
  const auto p = [&](std::size_t a) {
    Vec4 pa;
    pa << 1.0, q(a);
    return pa;
  };
  // From M b = p: db = M^+(dp - dM b) and d2b = M^+(-d2M b - 2 dM db) per axis (d2p = 0).
  Vec4 db[3], ddb[3];
  for (int d = 0; d < 3; ++d)
  {
    Mat4 dM = Mat4::Zero(), ddM = Mat4::Zero();
    for (std::size_t a = 0; a < n; ++a)
    {
      const Vec4 pa = p(a);
      const Mat4 ppT = pa * pa.transpose();
      dM.noalias() += dw[a][d] * ppT;
      ddM.noalias() += ddw[a][d] * ppT;
    }
    Vec4 dp = Vec4::Zero();
    dp[1 + d] = inverseScale;
    db[d] = Minv * (dp - dM * b);
    ddb[d] = Minv * (-ddM * b - 2.0 * dM * db[d]);
  }
  for (std::size_t a = 0; a < n; ++a)
  {
    const Vec4 pa = p(a);
    const double pb = pa.dot(b);
    double laplacian = 0;
    for (int d = 0; d < 3; ++d)
    {
      const double pdb = pa.dot(db[d]);
      out.gradient[a][d] = pdb * w[a] + pb * dw[a][d];
      laplacian += pa.dot(ddb[d]) * w[a] + 2.0 * pdb * dw[a][d] + pb * ddw[a][d];
    }
    out.laplacian[a] = laplacian;
    out.value[a] = w[a] * pb;
  }
}
} // namespace mlsdeform
