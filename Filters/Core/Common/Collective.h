// The processes that deform one distributed dataset together (MPI ranks under ParaView), seen
// by the core as a handful of collective operations. Every process calls the same operations in
// the same order; each returns the same result on every process. The base class is one process
// alone: gathering returns the local values and reductions leave them as they are.
//
// Results that must not depend on how the data is split use only exact reductions (maxima,
// integer sums) and gathered values put into a canonical order, never a floating-point sum over
// processes.
#pragma once

#include "Common/CoreTypes.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mlsdeform
{
class Collective
{
public:
  virtual ~Collective() = default;

  virtual int size() const { return 1; }
  virtual int rank() const { return 0; }

  /// Every process's values, concatenated in process order.
  virtual std::vector<double> gather(const std::vector<double>& local) const { return local; }
  virtual std::vector<std::int64_t> gather(const std::vector<std::int64_t>& local) const { return local; }

  /// Every process's values concatenated in process order on the first process; the others get
  /// nothing (data that only the first process needs, e.g. to write one file of the whole).
  virtual std::vector<double> gatherOnFirst(const std::vector<double>& local) const { return local; }

  /// Element-wise maximum over the processes, in place.
  virtual void maximum(std::vector<double>& values) const { (void)values; }

  /// Element-wise sum over the processes, in place (exact: integers).
  virtual void sum(std::vector<std::int64_t>& values) const { (void)values; }

  /// The first non-empty message in process order ("" when all are empty): a check that failed
  /// on some process, so that every process stops at the same point instead of waiting for the
  /// failed one in the next collective operation.
  virtual std::string firstError(const std::string& local) const { return local; }

  /// Whether any process says yes (a step that one process must redo is redone by all).
  bool any(bool local) const
  {
    std::vector<std::int64_t> value{ local ? 1 : 0 };
    sum(value);
    return value[0] > 0;
  }
};

/// Runs a step on this process's data (reading, checking it); when it throws on any process,
/// every process throws InvalidInputException with the first process's message, so that none
/// waits for the failed one in the next collective operation.
template <typename Step>
void agree(const Collective& group, Step step)
{
  std::string problem;
  try
  {
    step();
  }
  catch (const std::exception& e)
  {
    problem = e.what();
    problem = problem.empty() ? "unknown error" : problem;
  }
  problem = group.firstError(problem);
  if (!problem.empty())
  {
    throw InvalidInputException(group.size() > 1 ? problem + " (on one of " + std::to_string(group.size()) + " processes)" : problem);
  }
}

/// One process alone.
inline const Collective& serial()
{
  static const Collective alone;
  return alone;
}
} // namespace mlsdeform
