// The values of a float or double VTK array as a raw pointer, for the loops over a mesh's
// coordinates (or other 3-component arrays) that read or write them in place.
#pragma once

#include <vtkAOSDataArrayTemplate.h>
#include <vtkDataArray.h>

namespace mlsvtk
{
/// Calls f(values) with the array's values as float* or double* (contiguous tuples: component c of
/// tuple i at values[components * i + c]) and returns true; returns false without calling f when the
/// array holds another type or layout, which the caller then reads through vtkDataArray's virtual
/// accessors (GetTuple, GetPoint). f is instantiated for both types, so that a loop in it runs on
/// the pointer: no virtual call per value, which on a 1M-point mesh costs more than the loop's work.
template <typename F>
bool withTypedPoints(vtkDataArray* array, F&& f)
{
  if (auto* floats = vtkAOSDataArrayTemplate<float>::FastDownCast(array))
  {
    f(floats->GetPointer(0));
    return true;
  }
  if (auto* doubles = vtkAOSDataArrayTemplate<double>::FastDownCast(array))
  {
    f(doubles->GetPointer(0));
    return true;
  }
  return false;
}
} // namespace mlsvtk
