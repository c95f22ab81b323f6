#include "MLSBasis.h"

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

// a if take, else b, by a bit mask rather than a branch.
double select(bool take, double a, double b)
{
  std::uint64_t x, y;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  const std::uint64_t mask = ~static_cast<std::uint64_t>(0) * take;
  const std::uint64_t chosen = (x & mask) | (y & ~mask);
  double out;
  std::memcpy(&out, &chosen, sizeof out);
  return out;
}

// a[0] + a[1] y + ... + a[8] y^8 by Estrin's scheme: a third of Horner's chain of dependent
// operations, which bounded the weight loops.
double degree8(const double (&a)[9], double y)
{
  const double y2 = y * y, y4 = y2 * y2;
  const double low = (a[0] + a[1] * y) + (a[2] + a[3] * y) * y2;
  const double high = (a[4] + a[5] * y) + (a[6] + a[7] * y) * y2;
  return low + (high + a[8] * y4) * y4;
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
// Taylor coefficients in t^2 of sin t / t and of cos t (indexed by "is the cosine").
constexpr double Taylor[2][9] = { { 1, -1.0 / 6, 1.0 / 120, -1.0 / 5040, 1.0 / 362880, -1.0 / 39916800, 1.0 / 6227020800,
                                    -1.0 / 1307674368000, 1.0 / 355687428096000 },
  { 1, -1.0 / 2, 1.0 / 24, -1.0 / 720, 1.0 / 40320, -1.0 / 3628800, 1.0 / 479001600, -1.0 / 87178291200,
    1.0 / 20922789888000 } };

// s in [0, 1] reduced to t = pi u, u in [0, 1/4]: u = s, 1/2 - s, s - 1/2 or 1 - s, each
// difference exact (Sterbenz), and cos(pi s), sin(pi s) = (C, S), (S, C), (-S, C), (-C, S) of t.
// Chosen without branches: the cases come in no predictable order in the weight loops.
struct ReducedArgument
{
  bool upper; // s > 1/2: cos(pi s) = -sin(pi (s - 1/2))
  bool swap;  // the half-period argument above 1/4: C and S trade places
  double t;
};

ReducedArgument reduce(double s)
{
  const bool upper = s > 0.5;
  const double half = select(upper, s - 0.5, s); // in [0, 1/2]
  const bool swap = half > 0.25;
  return { upper, swap, M_PI * select(swap, 0.5 - half, half) };
}
}

void cosSinPi(double s, double& cosine, double& sine)
{
  const ReducedArgument r = reduce(s);
  const double t2 = r.t * r.t;
  const double C = degree8(Taylor[1], t2), S = r.t * degree8(Taylor[0], t2);
  const double c = select(r.swap, S, C), sn = select(r.swap, C, S); // of pi half
  cosine = select(r.upper, -sn, c);
  sine = select(r.upper, c, sn);
}

double cosPi(double s)
{
  // cos(pi s) = C, S, -S, -C: one of the two polynomials, the same bits as cosSinPi's cosine
  const ReducedArgument r = reduce(s);
  const double t2 = r.t * r.t;
  const bool cosinePolynomial = r.swap == r.upper;
  const double value = select(cosinePolynomial, 1.0, r.t) * degree8(Taylor[cosinePolynomial], t2);
  return select(r.upper, -value, value);
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
  return 0.5 * cosPi(r / sigma) + 0.5;
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

void MLSBasis::evaluateAmong(const Vec3& x, const std::vector<int>& candidates, ShapeFunctionValues& out, bool withDerivatives) const
{
  out.index.clear();
  out.value.clear();
  for (int j : candidates)
  {
    const double squared = (Centers[j] - x).squaredNorm();
    if (squared < Radii[j] * Radii[j]) // the test of KdTree::containing
    {
      out.index.push_back(j);
      out.value.push_back(squared);
    }
  }
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
    const double r = std::sqrt(out.value[a]);
    const double ratio = std::min(r / sigma, 1.0);
    double cosine, sine = 0; // of t = pi r / sigma; the sine only for derivatives
    if (withDerivatives)
    {
      cosSinPi(ratio, cosine, sine);
    }
    else
    {
      cosine = cosPi(ratio);
    }
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
      const Vec3 u = x - Centers[j];
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
