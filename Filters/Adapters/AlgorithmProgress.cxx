#include "Adapters/AlgorithmProgress.h"

#include <vtkAlgorithm.h>

namespace mlsvtk
{
void reportProgress(void* algorithm, double fraction)
{
  static_cast<vtkAlgorithm*>(algorithm)->UpdateProgress(fraction);
}
} // namespace mlsvtk
