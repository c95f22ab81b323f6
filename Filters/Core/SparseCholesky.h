// Supernodal sparse Cholesky factorization by CHOLMOD [28] (through Eigen), with CHOLMOD's
// estimate of the reciprocal condition number to reject singular systems.
#pragma once

#include "CoreTypes.h"

#include <Eigen/CholmodSupport>

namespace mlsdeform
{
class SparseCholesky : public Eigen::CholmodSupernodalLLT<SparseMatrix>
{
public:
  /// Failures are reported by info() and reciprocalCondition(), not printed by CHOLMOD.
  SparseCholesky() { this->cholmod().print = 0; }

  /// (min diag L / max diag L)^2, a cheap estimate of 1 / cond(K); 0 before a factorization.
  double reciprocalCondition()
  {
    return m_cholmodFactor && info() == Eigen::Success ? cholmod_rcond(m_cholmodFactor, &this->cholmod()) : 0.0;
  }
};
} // namespace mlsdeform
