#include "Solver/SparseCholesky.h"

#include <dlfcn.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mlsdeform
{
namespace
{
// Runs the BLAS on one thread for its lifetime: OpenMP's thread count (which OpenBLAS's OpenMP
// build follows) and, when the BLAS is OpenBLAS, its own count (its pthreads build).
class SerialBlas
{
public:
  SerialBlas()
    : Threads(omp_get_max_threads())
  {
    using Getter = int (*)();
    Set = reinterpret_cast<Setter>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    auto get = reinterpret_cast<Getter>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    BlasThreads = Set && get ? get() : 0;
    if (BlasThreads > 0)
    {
      Set(1);
    }
    omp_set_num_threads(1);
  }
  ~SerialBlas()
  {
    if (BlasThreads > 0)
    {
      Set(BlasThreads);
    }
    omp_set_num_threads(Threads);
  }
  SerialBlas(const SerialBlas&) = delete;
  SerialBlas& operator=(const SerialBlas&) = delete;

private:
  using Setter = void (*)(int);
  int Threads;
  Setter Set = nullptr;
  int BlasThreads = 0;
};
} // namespace

SparseCholesky::SparseCholesky()
{
  this->cholmod().print = 0; // failures are reported by factorize() and reciprocalCondition()
}

bool SparseCholesky::factorize(const SparseMatrix& A)
{
  SerialBlas serial;
  Diagonal = A.diagonal();
  this->compute(A);
  return this->info() == Eigen::Success;
}

Displacements SparseCholesky::solve(const Displacements& b) const
{
  SerialBlas serial;
  return Eigen::CholmodSupernodalLLT<SparseMatrix>::solve(b);
}

Eigen::VectorXd SparseCholesky::solveColumn(const Eigen::VectorXd& b) const
{
  SerialBlas serial;
  return Eigen::CholmodSupernodalLLT<SparseMatrix>::solve(b);
}

double SparseCholesky::reciprocalCondition()
{
  const cholmod_factor* L = m_cholmodFactor;
  if (!L || this->info() != Eigen::Success)
  {
    return 0.0;
  }
  if (!L->is_super || L->itype != CHOLMOD_INT || L->xtype != CHOLMOD_REAL || !(Diagonal.size() > 0 && Diagonal.minCoeff() > 0))
  {
    return cholmod_rcond(m_cholmodFactor, &this->cholmod());
  }
  // L L^T = P A P^T; the factor of the equilibrated P D A D P^T is diag(d_Perm[j]) L, so its
  // diagonal is L_jj / sqrt(A_Perm[j],Perm[j]). The diagonal entries of a supernode's columns,
  // as cholmod_rcond reads them: column j of supernode s at px[s] + (j - k1) * (nsrow + 1).
  const auto* super = static_cast<const int*>(L->super);
  const auto* pi = static_cast<const int*>(L->pi);
  const auto* px = static_cast<const int*>(L->px);
  const auto* perm = static_cast<const int*>(L->Perm);
  const auto* x = static_cast<const double*>(L->x);
  double smallest = std::numeric_limits<double>::infinity(), largest = 0;
  for (std::size_t s = 0; s < L->nsuper; ++s)
  {
    const int nsrow = pi[s + 1] - pi[s];
    for (int j = super[s]; j < super[s + 1]; ++j)
    {
      const double scaled = x[px[s] + (j - super[s]) * (nsrow + 1)] / std::sqrt(Diagonal[perm ? perm[j] : j]);
      smallest = std::min(smallest, scaled);
      largest = std::max(largest, scaled);
    }
  }
  return largest > 0 ? (smallest / largest) * (smallest / largest) : 0.0;
}
} // namespace mlsdeform
