// The core's progress reports (CoreTypes.h: Progress) passed on to a VTK algorithm.
#pragma once

namespace mlsvtk
{
/// Reports progress of the core to a VTK algorithm (client is a vtkAlgorithm*).
void reportProgress(void* algorithm, double fraction);
} // namespace mlsvtk
