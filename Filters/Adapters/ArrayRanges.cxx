#include "Adapters/ArrayRanges.h"

#include "Adapters/TypedPoints.h"

#include <vtkInformation.h>
#include <vtkInformationDoubleVectorKey.h>
#include <vtkInformationInformationVectorKey.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{
// Smallest and largest of each component and of the squared norm; finite when every squared norm is.
struct Ranges
{
  double low[4], high[4];
  bool finite = true;

  Ranges()
  {
    std::fill(low, low + 4, std::numeric_limits<double>::max());
    std::fill(high, high + 4, std::numeric_limits<double>::lowest());
  }

  void merge(const Ranges& other)
  {
    for (int c = 0; c < 4; ++c)
    {
      low[c] = std::min(low[c], other.low[c]);
      high[c] = std::max(high[c], other.high[c]);
    }
    finite = finite && other.finite;
  }
};

// The ranges of n tuples of 3 values, in one parallel pass.
template <typename T>
Ranges rangesOf(const T* values, long n)
{
  Ranges all;
#pragma omp parallel
  {
    Ranges mine;
#pragma omp for schedule(static) nowait
    for (long i = 0; i < n; ++i)
    {
      double squaredNorm = 0; // in double, as vtkDataArray's vector range
      for (int c = 0; c < 3; ++c)
      {
        const double v = values[3 * i + c];
        mine.low[c] = std::min(mine.low[c], v);
        mine.high[c] = std::max(mine.high[c], v);
        squaredNorm += v * v;
      }
      mine.finite = mine.finite && std::isfinite(squaredNorm); // a non-finite value, or a norm VTK's finite range skips
      mine.low[3] = std::min(mine.low[3], squaredNorm);
      mine.high[3] = std::max(mine.high[3], squaredNorm);
    }
#pragma omp critical
    all.merge(mine); // min, max and 'and' are exact in any order: the same for any thread count
  }
  return all;
}

// The ranges into the array's range cache, where vtkDataArray looks for them.
void store(vtkDataArray* array, const Ranges& all)
{
  vtkInformation* info = array->GetInformation();
  const double norm[2] = { std::sqrt(all.low[3]), std::sqrt(all.high[3]) };
  info->Set(vtkDataArray::L2_NORM_RANGE(), norm, 2);
  info->Set(vtkDataArray::L2_NORM_FINITE_RANGE(), norm, 2);
  for (vtkInformationInformationVectorKey* key : { vtkAbstractArray::PER_COMPONENT(), vtkAbstractArray::PER_FINITE_COMPONENT() })
  {
    vtkNew<vtkInformationVector> components;
    components->SetNumberOfInformationObjects(3);
    for (int c = 0; c < 3; ++c)
    {
      const double range[2] = { all.low[c], all.high[c] };
      components->GetInformationObject(c)->Set(vtkDataArray::COMPONENT_RANGE(), range, 2);
    }
    info->Set(key, components);
  }
}
}

void mlsvtk::storeRanges(vtkDataArray* array)
{
  const long n = array->GetNumberOfTuples();
  Ranges all;
  const bool typed = array->GetNumberOfComponents() == 3 && withTypedPoints(array, [&](const auto* values) { all = rangesOf(values, n); });
  if (typed && all.finite && n > 0)
  {
    store(array, all);
  }
}
