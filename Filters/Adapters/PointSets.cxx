#include "Adapters/PointSets.h"

#include "Adapters/TypedPoints.h"

#include <vtkCellArray.h>
#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <algorithm>

namespace mlsvtk
{
std::vector<vtkPointSet*> pointSets(vtkDataObject* input, int* skipped)
{
  std::vector<vtkPointSet*> sets;
  int others = 0;
  if (auto* set = vtkPointSet::SafeDownCast(input))
  {
    sets.push_back(set);
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it = vtkSmartPointer<vtkCompositeDataIterator>::Take(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (auto* leaf = vtkPointSet::SafeDownCast(it->GetCurrentDataObject()))
      {
        sets.push_back(leaf);
      }
      else
      {
        ++others;
      }
    }
  }
  else if (input)
  {
    ++others;
  }
  if (skipped)
  {
    *skipped = others;
  }
  return sets;
}

void copyPoints(vtkPointSet* set, mlsdeform::Vec3* out)
{
  const vtkIdType n = set->GetNumberOfPoints();
  // in parallel: fresh memory is first touched, and zeroed by the kernel, on every core
  auto copy = [&](const auto* in) {
#pragma omp parallel for schedule(static)
    for (vtkIdType i = 0; i < n; ++i)
    {
      out[i] = mlsdeform::Vec3(in[3 * i], in[3 * i + 1], in[3 * i + 2]);
    }
  };
  if (n > 0 && !withTypedPoints(set->GetPoints()->GetData(), copy))
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      set->GetPoint(i, out[i].data());
    }
  }
}

mlsdeform::PointList points(const std::vector<vtkPointSet*>& sets)
{
  mlsdeform::PointList out;
  for (vtkPointSet* set : sets)
  {
    const std::size_t offset = out.size();
    out.resize(offset + set->GetNumberOfPoints());
    copyPoints(set, out.data() + offset);
  }
  return out;
}

vtkSmartPointer<vtkDoubleArray> triangleCorners(const std::vector<vtkPointSet*>& sets, const char* name)
{
  auto corners = vtkSmartPointer<vtkDoubleArray>::New();
  corners->SetName(name);
  corners->SetNumberOfComponents(9);
  vtkNew<vtkGenericCell> cell;
  vtkNew<vtkIdList> ids;
  vtkNew<vtkPoints> points;
  for (vtkPointSet* set : sets)
  {
    for (vtkIdType c = 0; c < set->GetNumberOfCells(); ++c)
    {
      set->GetCell(c, cell);
      if (cell->GetCellDimension() != 2)
      {
        continue;
      }
      cell->Triangulate(0, ids, points); // 3 points per triangle
      for (vtkIdType k = 0; k + 2 < points->GetNumberOfPoints(); k += 3)
      {
        double triangle[9];
        for (int j = 0; j < 3; ++j)
        {
          points->GetPoint(k + j, triangle + 3 * j);
        }
        corners->InsertNextTuple(triangle);
      }
    }
  }
  return corners;
}

vtkSmartPointer<vtkPolyData> pointCloud(const mlsdeform::PointList& positions,
  const std::vector<std::pair<std::string, const std::vector<double>*>>& arrays)
{
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(positions.size()));
  vtkNew<vtkCellArray> vertices;
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    pts->SetPoint(static_cast<vtkIdType>(i), positions[i].data());
    const vtkIdType id = static_cast<vtkIdType>(i);
    vertices->InsertNextCell(1, &id);
  }
  cloud->SetPoints(pts);
  cloud->SetVerts(vertices);
  for (const auto& [name, values] : arrays)
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(name.c_str());
    array->SetNumberOfValues(static_cast<vtkIdType>(values->size()));
    std::copy(values->begin(), values->end(), array->GetPointer(0));
    cloud->GetPointData()->AddArray(array);
  }
  return cloud;
}
} // namespace mlsvtk
