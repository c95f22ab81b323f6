// The shape functions phi_1..phi_k of a deformation subspace d(x) = sum_j w_j phi_j(x) (paper
// sections 3 and 4): the mesh's piecewise linear functions (eq. 5), MLS (section 4) and others.
#pragma once

#include "Common/CoreTypes.h"

#include <cmath>
#include <string>

namespace mlsdeform
{
/// The shape functions that do not vanish at one position, and optionally their derivatives.
struct ShapeFunctionValues
{
  std::vector<int> index;        // j
  std::vector<double> value;     // phi_j(x)
  std::vector<Vec3> gradient;    // grad phi_j(x)   (when derivatives were asked for)
  std::vector<double> laplacian; // Laplacian phi_j(x) (when derivatives were asked for)
  bool empty() const { return index.empty(); }
};

class ShapeFunctions
{
public:
  virtual ~ShapeFunctions() = default;

  /// Evaluates at x; the result is empty where no shape function is defined (outside every
  /// support). Thread-safe.
  virtual void evaluate(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const = 0;

  /// Lets nearby positions share one search: the indices j whose support may meet the box
  /// [lower, upper], in increasing order; false when the basis has no such search.
  virtual bool candidatesInBox(const Vec3& /*lower*/, const Vec3& /*upper*/, std::vector<int>& /*candidates*/) const
  {
    return false;
  }
  /// The candidates of a box narrowed to those that may meet the box [lower, upper] inside it
  /// (increasing): candidates for its positions, fewer to test each.
  virtual void narrowCandidates(const Vec3& /*lower*/, const Vec3& /*upper*/, const std::vector<int>& candidates, std::vector<int>& narrowed) const
  {
    narrowed = candidates;
  }
  /// evaluate(x, ...) given the candidates of a box holding x; the same result.
  virtual void evaluateAmong(const Vec3& x, const std::vector<int>& /*candidates*/, ShapeFunctionValues& out, bool withDerivatives) const
  {
    evaluate(x, out, withDerivatives);
  }

  /// k, the number of shape functions.
  virtual std::size_t size() const = 0;
};

/// Compact shape functions need one positive, finite support radius per center; throws
/// InvalidInputException naming the basis otherwise.
inline void requireSupportRadii(const PointList& centers, const std::vector<double>& radii, const std::string& basis)
{
  if (centers.size() != radii.size())
  {
    throw InvalidInputException(basis + " basis: one support radius per center is needed");
  }
  for (double r : radii)
  {
    if (!(r > 0) || !std::isfinite(r))
    {
      throw InvalidInputException(basis + " basis: support radii must be positive and finite");
    }
  }
}
} // namespace mlsdeform
