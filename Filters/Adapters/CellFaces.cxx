#include "Adapters/CellFaces.h"

#include <vtkCell.h>
#include <vtkCellType.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkNew.h>

#include <array>
#include <utility>

namespace mlsvtk
{
const LocalFaces& cellTypeFaces(int type)
{
  // The types whose faces follow from the type alone. A higher-order cell's faces depend on its
  // number of points (its order), which a cell made from the type alone does not have.
  static const std::array<LocalFaces, VTK_NUMBER_OF_CELL_TYPES> faces = [] {
    std::array<LocalFaces, VTK_NUMBER_OF_CELL_TYPES> out;
    vtkNew<vtkGenericCell> cell;
    for (int fixed : { VTK_TETRA, VTK_VOXEL, VTK_HEXAHEDRON, VTK_WEDGE, VTK_PYRAMID, VTK_PENTAGONAL_PRISM,
           VTK_HEXAGONAL_PRISM, VTK_QUADRATIC_TETRA, VTK_QUADRATIC_HEXAHEDRON, VTK_QUADRATIC_WEDGE,
           VTK_QUADRATIC_PYRAMID, VTK_TRIQUADRATIC_HEXAHEDRON, VTK_QUADRATIC_LINEAR_WEDGE,
           VTK_BIQUADRATIC_QUADRATIC_WEDGE, VTK_BIQUADRATIC_QUADRATIC_HEXAHEDRON, VTK_TRIQUADRATIC_PYRAMID })
    {
      // a cell whose point ids are 0 .. n-1: its faces' point ids are positions in its point list
      cell->SetCellType(fixed);
      for (vtkIdType i = 0; i < cell->GetPointIds()->GetNumberOfIds(); ++i)
      {
        cell->GetPointIds()->SetId(i, i);
      }
      for (int f = 0; f < cell->GetNumberOfFaces(); ++f)
      {
        vtkCell* face = cell->GetFace(f);
        vtkIdList* ids = face->GetPointIds();
        std::vector<int> polygon(ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfIds());
        if (face->GetCellType() == VTK_PIXEL)
        {
          std::swap(polygon[2], polygon[3]); // a pixel's points in raster order, not around it
        }
        else if (face->GetCellType() == VTK_QUADRATIC_TRIANGLE || face->GetCellType() == VTK_QUADRATIC_QUAD ||
          face->GetCellType() == VTK_BIQUADRATIC_QUAD)
        {
          // the corners, then the midside nodes: around the face, each midside node between its
          // corners (a biquadratic face's centre left out)
          const std::size_t corners = face->GetCellType() == VTK_QUADRATIC_TRIANGLE ? 3 : 4;
          std::vector<int> around;
          for (std::size_t i = 0; i < corners; ++i)
          {
            around.push_back(polygon[i]);
            around.push_back(polygon[corners + i]);
          }
          polygon = around;
        }
        out[fixed].push_back(polygon);
      }
    }
    return out;
  }();
  return type >= 0 && type < VTK_NUMBER_OF_CELL_TYPES ? faces[type] : faces[VTK_EMPTY_CELL];
}
} // namespace mlsvtk
