// Supernodal sparse Cholesky factorization by CHOLMOD [28] (through Eigen), with CHOLMOD's
// estimate of the reciprocal condition number to reject singular systems.
//
// The BLAS runs on one thread inside: OpenBLAS's threaded dpotrf and dgemm split their work by
// the number of threads and so round differently (measured: factors that differ in the last
// bits with 1 and 2 threads), and a design variant must not depend on the machine's cores. The
// factorization is a small part of a set-up (sampling and the energies dominate), and a solve
// with three right-hand sides gains little from threads.
#pragma once

#include "Common/CoreTypes.h"

#include <Eigen/CholmodSupport>

namespace mlsdeform
{
class SparseCholesky : private Eigen::CholmodSupernodalLLT<SparseMatrix>
{
public:
  SparseCholesky();

  /// Factorizes the symmetric matrix A (its lower triangle is read); false when it is not
  /// positive definite.
  bool factorize(const SparseMatrix& A);

  /// A^-1 b, after a successful factorize.
  Displacements solve(const Displacements& b) const;
  Eigen::VectorXd solveColumn(const Eigen::VectorXd& b) const;

  /// (min diag L / max diag L)^2, a cheap estimate of 1 / cond(A); 0 before a factorization.
  double reciprocalCondition();
};
} // namespace mlsdeform
