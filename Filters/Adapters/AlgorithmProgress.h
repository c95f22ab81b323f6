// The core's progress reports (CoreTypes.h: Progress) passed on to a VTK algorithm, and its cancel
// (ParaView's progress bar) checked between the stages of a long computation.
#pragma once

#include "Common/Collective.h"

class vtkAlgorithm;

namespace mlsvtk
{
/// Reports progress of the core to a VTK algorithm (client is a vtkAlgorithm*).
void reportProgress(void* algorithm, double fraction);

/// Throws mlsdeform::AbortedException when the algorithm was asked to stop
/// (vtkAlgorithm::CheckAbort) on any process of group; every process must call it at the same step.
/// The request is consumed (AbortExecute cleared): it stops this update, and the next one runs.
void checkAbort(vtkAlgorithm* algorithm, const mlsdeform::Collective& group = mlsdeform::serial());
} // namespace mlsvtk
