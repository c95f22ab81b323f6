#include "Adapters/Stamp.h"

#include <vtkCellArray.h>
#include <vtkObject.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

namespace mlsvtk
{
void Stamp::add(vtkObject* object)
{
  objects.emplace_back(object, object ? object->GetMTime() : 0);
}

Stamp pointsStamp(const std::vector<vtkPointSet*>& sets)
{
  Stamp stamp;
  for (vtkPointSet* set : sets)
  {
    stamp.add(set->GetPoints()); // vtkPoints' MTime includes its data array's
  }
  return stamp;
}

Stamp cellsStamp(const std::vector<vtkPointSet*>& sets)
{
  Stamp stamp;
  // a cell array's MTime does not include its storage arrays': both count
  auto addCells = [&stamp](vtkCellArray* cells) {
    stamp.add(cells);
    stamp.add(cells ? cells->GetOffsetsArray() : nullptr);
    stamp.add(cells ? cells->GetConnectivityArray() : nullptr);
  };
  for (vtkPointSet* set : sets)
  {
    if (auto* poly = vtkPolyData::SafeDownCast(set))
    {
      addCells(poly->GetVerts());
      addCells(poly->GetLines());
      addCells(poly->GetPolys());
      addCells(poly->GetStrips());
    }
    else if (auto* grid = vtkUnstructuredGrid::SafeDownCast(set))
    {
      addCells(grid->GetCells());
      stamp.add(grid->GetCellTypesArray());
      stamp.add(grid->GetFaces());
      stamp.add(grid->GetFaceLocations());
    }
    else
    {
      stamp.add(set); // another point set type: any modification counts
    }
  }
  return stamp;
}
} // namespace mlsvtk
