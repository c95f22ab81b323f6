#include "Solver/SparseCholesky.h"

#include <dlfcn.h>
#include <omp.h>

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
  return m_cholmodFactor && this->info() == Eigen::Success ? cholmod_rcond(m_cholmodFactor, &this->cholmod()) : 0.0;
}
} // namespace mlsdeform
