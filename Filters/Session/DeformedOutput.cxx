#include "Session/DeformedOutput.h"

#include "Adapters/ArrayRanges.h"
#include "Adapters/TypedPoints.h"
#include "Vocabulary/FieldNames.h"

#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>

#include <type_traits>

using namespace mlsdeform;

namespace mlsvtk
{
void copyInput(vtkDataObject* input, vtkDataObject* output)
{
  auto* inComposite = vtkCompositeDataSet::SafeDownCast(input);
  auto* outComposite = vtkCompositeDataSet::SafeDownCast(output);
  if (inComposite && outComposite)
  {
    outComposite->CopyStructure(inComposite);
    vtkSmartPointer<vtkCompositeDataIterator> it = vtkSmartPointer<vtkCompositeDataIterator>::Take(inComposite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      vtkDataObject* leaf = it->GetCurrentDataObject();
      vtkSmartPointer<vtkDataObject> copy = vtkSmartPointer<vtkDataObject>::Take(leaf->NewInstance());
      copy->ShallowCopy(leaf);
      outComposite->SetDataSet(it, copy);
    }
    outComposite->GetFieldData()->ShallowCopy(inComposite->GetFieldData());
  }
  else
  {
    output->ShallowCopy(input);
  }
}

namespace
{
// An output array of the previous update, to be written again, when it fits and no one but this
// object holds it (the output released it when it was reset to the input); else a new one.
template <typename Object>
Object* reusable(vtkSmartPointer<Object>& kept, bool fits)
{
  if (!kept || !fits || kept->GetReferenceCount() > 1)
  {
    kept = vtkSmartPointer<Object>::New();
  }
  return kept;
}
}

bool DeformedOutput::fits(std::size_t s, vtkPointSet* in) const
{
  const vtkIdType n = in->GetNumberOfPoints();
  return n == 0 ||
    (s < Moved.size() && Moved[s] && Moved[s]->GetNumberOfPoints() == n && Moved[s]->GetDataType() == in->GetPoints()->GetDataType() &&
      Displacement[s] && Displacement[s]->GetNumberOfTuples() == n);
}

void DeformedOutput::keep(std::size_t s, vtkPointSet* out) const
{
  if (out->GetNumberOfPoints() > 0)
  {
    out->SetPoints(Moved[s]);
    out->GetPointData()->AddArray(Displacement[s]);
    for (vtkDataArray* array : Derived[s])
    {
      out->GetPointData()->AddArray(array);
    }
  }
}

void DeformedOutput::addDerived(std::size_t s, vtkDataArray* array)
{
  Derived[s].emplace_back(array);
}

bool DeformedOutput::restore(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets)
{
  for (std::size_t s = 0; s < inSets.size(); ++s)
  {
    if (!fits(s, inSets[s]))
    {
      return false;
    }
  }
  for (std::size_t s = 0; s < inSets.size(); ++s)
  {
    keep(s, outSets[s]);
  }
  return true;
}

void DeformedOutput::write(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets, const PointList& points,
  const DisplacementField& displace, const std::vector<char>& moving)
{
  Moved.resize(inSets.size());
  Displacement.resize(inSets.size());
  Derived.resize(inSets.size());
  long offset = 0;
  for (std::size_t s = 0; s < inSets.size(); ++s)
  {
    const vtkIdType n = inSets[s]->GetNumberOfPoints();
    if (n == 0)
    {
      continue;
    }
    const int type = inSets[s]->GetPoints()->GetDataType();
    if (!moving[s] && fits(s, inSets[s]))
    {
      keep(s, outSets[s]); // unchanged since the previous write
      offset += n;
      continue;
    }
    Derived[s].clear();
    vtkDoubleArray* displacement = reusable(Displacement[s], Displacement[s] && Displacement[s]->GetNumberOfTuples() == n);
    displacement->SetName(fields::Displacement);
    displacement->SetNumberOfComponents(3);
    displacement->SetNumberOfTuples(n);
    displace(offset, n, displacement->GetPointer(0));
    displacement->Modified();
    vtkPoints* moved = reusable(Moved[s], Moved[s] && Moved[s]->GetNumberOfPoints() == n && Moved[s]->GetDataType() == type);
    moved->SetDataType(type);
    moved->SetNumberOfPoints(n);
    const double* d = displacement->GetPointer(0);
    const bool written = withTypedPoints(moved->GetData(), [&](auto* out) {
      using Value = std::remove_pointer_t<decltype(out)>;
#pragma omp parallel for schedule(dynamic, 16384) // as threads come free (multiplyRows)
      for (vtkIdType i = 0; i < n; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          out[3 * i + c] = static_cast<Value>(points[offset + i][c] + d[3 * i + c]);
        }
      }
    });
    if (!written)
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        const Vec3 x = points[offset + i] + Vec3(displacement->GetPointer(3 * i));
        moved->SetPoint(i, x.data());
      }
    }
    moved->Modified();
    storeRanges(displacement);
    storeRanges(moved->GetData());
    offset += n;
    outSets[s]->SetPoints(moved);
    outSets[s]->GetPointData()->AddArray(displacement);
  }
}
} // namespace mlsvtk
