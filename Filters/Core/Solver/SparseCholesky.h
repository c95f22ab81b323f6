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

  /// (min diag L / max diag L)^2 of the factor of the Jacobi-equilibrated D A D (D =
  /// diag(A)^-1/2), read off A's factor: a cheap estimate of 1 / cond(D A D); 0 before a
  /// factorization. Equilibrated, it is blind to the rows' scales alone: on a graded mesh the
  /// samples' rows of eq. 14 differ in scale by orders of magnitude (a support's integration
  /// volumes and derivatives scale with its size), which costs Cholesky no accuracy (van der
  /// Sluis), while A's own estimate fell below the singularity threshold on systems the
  /// equilibrated one finds well determined (the sphereChannel case with k = 4000: 6e-6 for A,
  /// 1e-3 for D A D).
  double reciprocalCondition();

private:
  Eigen::VectorXd Diagonal; // A's, for the equilibrated estimate
};
} // namespace mlsdeform
