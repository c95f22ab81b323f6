// Radial basis function subspaces, the alternatives to MLS compared in paper section 4 (Fig. 3, 4):
//   Wendland     phi(r) = (1 - r/sigma)^4 (4 r/sigma + 1) for r < sigma   (compact, C2 [29])
//   Gaussian     phi(r) = exp(-r^2/h^2), h = sigma/3, truncated at sigma: shifted and scaled so
//                that it is 1 at r = 0 and goes continuously to 0 at sigma (the tail cut off is
//                exp(-9) = 1.2e-4)
//   Biharmonic   phi(r) = r                                                (global)
//   Triharmonic  phi(r) = r^3                                              (global)
// The paper prints the triharmonic kernel as ||x - c||^2; r^3 is the triharmonic (polyharmonic
// of order 3) kernel in 3D [29, 32]. The global kernels carry the linear polynomials 1, x, y, z
// as four more shape functions, so that translations and linear maps lie in the subspace; their
// radii are measured in units of the centers' bounding box. Every point depends on every center,
// so Phi and the k x k system are dense. Compact kernels use the cover rule's support radii and
// reproduce neither constants nor linear functions (the source of their artifacts in Fig. 3).
#pragma once

#include "Common/KdTree.h"
#include "Basis/ShapeFunctions.h"

namespace mlsdeform
{
enum class RadialKernel
{
  Wendland,
  Gaussian,
  Biharmonic,
  Triharmonic
};

class RadialBasis : public ShapeFunctions
{
public:
  /// Kernels centered at c_j; the support radii sigma_j are used by the compact kernels only.
  RadialBasis(RadialKernel kernel, const PointList& centers, const std::vector<double>& supportRadii);

  void evaluate(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const override;

  /// k centers, plus the 4 linear polynomials for a global kernel.
  std::size_t size() const override { return Centers.size() + (global() ? 4 : 0); }

  bool global() const { return Kernel == RadialKernel::Biharmonic || Kernel == RadialKernel::Triharmonic; }

private:
  /// phi(r), phi'(r)/r and the Laplacian phi'' + 2 phi'/r of the kernel with support sigma.
  struct Profile
  {
    double value = 0, derivativeOverR = 0, laplacian = 0;
  };
  Profile profile(double r, double sigma) const;

  RadialKernel Kernel;
  PointList Centers;
  std::vector<double> Radii;
  KdTree Supports;       // compact kernels
  Vec3 Origin;           // global kernels: the polynomials are (1, (x - Origin) / Scale)
  double Scale = 1;
};
} // namespace mlsdeform
