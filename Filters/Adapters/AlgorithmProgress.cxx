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
bool abortRequested(void* algorithm)
{
  return static_cast<vtkAlgorithm*>(algorithm)->GetAbortExecute() != 0;
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
