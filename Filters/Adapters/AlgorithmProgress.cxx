#include "Adapters/AlgorithmProgress.h"

#include <vtkAlgorithm.h>

namespace mlsvtk
{
void reportProgress(void* algorithm, double fraction)
{
  static_cast<vtkAlgorithm*>(algorithm)->UpdateProgress(fraction);
}

namespace
{
// Asked at the core's checks: the progress is reported again first, so that a GUI listening to it
// can take a cancel between two of the core's reports (ParaView's progress bar, pqSetUpCancel).
bool abortRequested(void* client)
{
  auto* algorithm = static_cast<vtkAlgorithm*>(client);
  algorithm->UpdateProgress(algorithm->GetProgress());
  return algorithm->GetAbortExecute() != 0;
}
}

mlsdeform::Progress progressOf(vtkAlgorithm* algorithm, double begin, double end, const mlsdeform::Collective& group)
{
  return { &reportProgress, algorithm, begin, end, group.size() == 1 ? &abortRequested : nullptr };
}

void checkAbort(vtkAlgorithm* algorithm, const mlsdeform::Collective& group)
{
  if (group.any(algorithm->CheckAbort()))
  {
    throw mlsdeform::AbortedException("cancelled");
  }
}
} // namespace mlsvtk
