#include "Solver/LinearizedFixedPoint.h"

#include "Common/CoreTypes.h"

#include <Eigen/Dense>

#include <cmath>
#include <string>
#include <vector>

namespace mlsdeform
{
namespace
{
constexpr double RelativeStep = 1e-4;
constexpr double Tolerance = 1e-10;
constexpr int MaxProducts = 300;
}

double centralDifferenceStep(double length, double largestComponent)
{
  return largestComponent > 0 ? RelativeStep * length / largestComponent : 0.0;
}

Eigen::VectorXd solveIdentityMinus(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& M, const Eigen::VectorXd& r)
{
  const double beta = r.norm();
  if (!(beta > 0))
  {
    return Eigen::VectorXd::Zero(r.size());
  }
  // Arnoldi with modified Gram-Schmidt; Givens rotations keep the least-squares problem
  // min |beta e1 - H y| triangular, its residual is |g(j + 1)|.
  std::vector<Eigen::VectorXd> V{ r / beta };
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(MaxProducts + 1, MaxProducts);
  Eigen::VectorXd cs = Eigen::VectorXd::Zero(MaxProducts), sn = Eigen::VectorXd::Zero(MaxProducts);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(MaxProducts + 1);
  g(0) = beta;
  int j = 0;
  for (; j < MaxProducts; ++j)
  {
    Eigen::VectorXd w = V[j] - M(V[j]);
    for (int i = 0; i <= j; ++i)
    {
      H(i, j) = w.dot(V[i]);
      w -= H(i, j) * V[i];
    }
    H(j + 1, j) = w.norm();
    for (int i = 0; i < j; ++i)
    {
      const double t = cs(i) * H(i, j) + sn(i) * H(i + 1, j);
      H(i + 1, j) = -sn(i) * H(i, j) + cs(i) * H(i + 1, j);
      H(i, j) = t;
    }
    const double d = std::hypot(H(j, j), H(j + 1, j));
    cs(j) = H(j, j) / d;
    sn(j) = H(j + 1, j) / d;
    H(j, j) = d;
    H(j + 1, j) = 0;
    g(j + 1) = -sn(j) * g(j);
    g(j) = cs(j) * g(j);
    const bool done = std::abs(g(j + 1)) <= Tolerance * beta;
    if (done || !(w.norm() > 0))
    {
      ++j;
      break;
    }
    V.push_back(w / w.norm());
  }
  if (std::abs(g(j)) > Tolerance * beta && j >= MaxProducts)
  {
    throw SolverException("the derivative of the constraint iteration's fixed point did not converge in " +
      std::to_string(MaxProducts) + " GMRES steps (relative residual " + std::to_string(std::abs(g(j)) / beta) +
      "): the constraints conflict with the targets there");
  }
  const Eigen::VectorXd y = H.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(r.size());
  for (int i = 0; i < j; ++i)
  {
    x += y(i) * V[i];
  }
  return x;
}
} // namespace mlsdeform
