#include "Basis/RadialBasis.h"

#include "Common/BoundingBox.h"

#include <cmath>
#include <numeric>

namespace mlsdeform
{
namespace
{
// The Gaussian's width: h = sigma / GaussianWidths, truncated at sigma.
constexpr double GaussianWidths = 3;
}

RadialBasis::RadialBasis(RadialKernel kernel, const PointList& centers, const std::vector<double>& supportRadii)
  : Kernel(kernel)
  , Centers(centers)
  , Radii(supportRadii)
{
  if (centers.empty())
  {
    throw InvalidInputException("RBF basis: no centers");
  }
  requireFinite(centers, "RBF centers");
  const BoundingBox box = boundingBox(centers);
  Origin = (box.lower + box.upper) / 2;
  Scale = std::max(box.size().maxCoeff(), 1e-300);
  if (global())
  {
    return;
  }
  requireSupportRadii(centers, supportRadii, "RBF");
  Supports.build(centers);
  Supports.setRadii(supportRadii);
}

RadialBasis::Profile RadialBasis::profile(double r, double sigma) const
{
  Profile p;
  switch (Kernel)
  {
    case RadialKernel::Wendland:
    {
      // phi' / r = -20 (1 - t)^3 / sigma^2, phi'' + 2 phi'/r = -60 (1 - t)^2 (1 - 2t) / sigma^2
      const double t = r / sigma, s = 1 - t;
      p.value = s * s * s * s * (4 * t + 1);
      p.derivativeOverR = -20 * s * s * s / (sigma * sigma);
      p.laplacian = -60 * s * s * (1 - 2 * t) / (sigma * sigma);
      break;
    }
    case RadialKernel::Gaussian:
    {
      // (exp(-a r^2) - exp(-a sigma^2)) / (1 - exp(-a sigma^2)) with a = (3 / sigma)^2
      const double a = GaussianWidths * GaussianWidths / (sigma * sigma);
      const double tail = std::exp(-GaussianWidths * GaussianWidths), e = std::exp(-a * r * r) / (1 - tail);
      p.value = e - tail / (1 - tail);
      p.derivativeOverR = -2 * a * e;
      p.laplacian = (4 * a * a * r * r - 6 * a) * e;
      break;
    }
    case RadialKernel::Biharmonic:
    {
      // rho = r / Scale: phi = rho, phi'/r = 1 / (Scale r), Laplacian 2 / (Scale r); the kernel
      // is not differentiable at its center, which integration points do not hit (r >= 1e-9 Scale)
      const double rho = std::max(r, 1e-9 * Scale);
      p.value = r / Scale;
      p.derivativeOverR = 1 / (Scale * rho);
      p.laplacian = 2 / (Scale * rho);
      break;
    }
    case RadialKernel::Triharmonic:
    {
      // phi = rho^3: phi'/r = 3 r / Scale^3, phi'' = 6 r / Scale^3, Laplacian 12 r / Scale^3
      const double s3 = Scale * Scale * Scale;
      p.value = r * r * r / s3;
      p.derivativeOverR = 3 * r / s3;
      p.laplacian = 12 * r / s3;
      break;
    }
  }
  return p;
}

void RadialBasis::evaluate(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const
{
  const int k = static_cast<int>(Centers.size());
  if (global())
  {
    out.index.resize(size());
    std::iota(out.index.begin(), out.index.end(), 0);
  }
  else
  {
    Supports.containing(x, out.index);
  }
  const std::size_t n = out.index.size();
  out.value.resize(n);
  out.gradient.resize(withDerivatives ? n : 0);
  out.laplacian.resize(withDerivatives ? n : 0);
  for (std::size_t a = 0; a < n; ++a)
  {
    const int j = out.index[a];
    if (j >= k)
    {
      // the linear polynomials of a global kernel: 1, (x_d - Origin_d) / Scale
      const int d = j - k - 1;
      out.value[a] = d < 0 ? 1.0 : (x[d] - Origin[d]) / Scale;
      if (withDerivatives)
      {
        out.gradient[a] = d < 0 ? Vec3::Zero() : Vec3(Vec3::Unit(d) / Scale);
        out.laplacian[a] = 0;
      }
      continue;
    }
    const Vec3 u = x - Centers[j];
    const Profile p = profile(u.norm(), global() ? 1.0 : Radii[j]);
    out.value[a] = p.value;
    if (withDerivatives)
    {
      out.gradient[a] = p.derivativeOverR * u;
      out.laplacian[a] = p.laplacian;
    }
  }
}
} // namespace mlsdeform
