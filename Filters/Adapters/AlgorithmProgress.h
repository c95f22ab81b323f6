// The core's progress reports (CoreTypes.h: Progress) passed on to a VTK algorithm, and its cancel
// (ParaView's progress bar) checked between the stages of a long computation.
#pragma once

#include "Common/Collective.h"
#include "Common/CoreTypes.h"

class vtkAlgorithm;

namespace mlsvtk
{
/// Reports progress of the core to a VTK algorithm (client is a vtkAlgorithm*).
void reportProgress(void* algorithm, double fraction);

/// The core's progress for the part [begin, end] of the algorithm's update. On one process the
/// core also stops at its own checks (within a stage) when the algorithm is asked to stop
/// (AbortExecute); under MPI the processes stop together, between stages (checkAbort).
mlsdeform::Progress progressOf(vtkAlgorithm* algorithm, double begin = 0, double end = 1,
  const mlsdeform::Collective& group = mlsdeform::serial());

/// Throws mlsdeform::AbortedException when the algorithm was asked to stop
/// (vtkAlgorithm::CheckAbort) on any process of group; every process must call it at the same step.
/// The request stops this update only: reportFailure (FailurePolicy.h) clears it.
void checkAbort(vtkAlgorithm* algorithm, const mlsdeform::Collective& group = mlsdeform::serial());
} // namespace mlsvtk
