#include "Adapters/AlgorithmProgress.h"

#include <vtkAlgorithm.h>

namespace mlsvtk
{
void reportProgress(void* algorithm, double fraction)
{
  static_cast<vtkAlgorithm*>(algorithm)->UpdateProgress(fraction);
}

void checkAbort(vtkAlgorithm* algorithm, const mlsdeform::Collective& group)
{
  if (group.any(algorithm->CheckAbort()))
  {
    algorithm->SetAbortExecute(0); // the request stops this update only: the next one runs
    throw mlsdeform::AbortedException("cancelled; what finished before is kept for the next update");
  }
}
} // namespace mlsvtk
