#include "Adapters/MeshVolume.h"

#include "Adapters/MeshCells.h"
#include "Adapters/VolumeMeshQuality.h"
#include "Quality/FaceQualityAggregate.h"
#include "Structural/ShapeSensitivity.h"

#include <vtkUnstructuredGrid.h>

#include <optional>

namespace mlsvtk
{
namespace
{
// The CalculiX element of an ElementJacobian shape (both in VTK's node order).
mlsdeform::SolidElement solidElement(mlsdeform::ElementShape shape)
{
  using mlsdeform::ElementShape;
  using mlsdeform::SolidElement;
  switch (shape)
  {
    case ElementShape::Tetra4: return SolidElement::C3D4;
    case ElementShape::Tetra10: return SolidElement::C3D10;
    case ElementShape::Hexa8: return SolidElement::C3D8;
    case ElementShape::Hexa20: return SolidElement::C3D20;
    case ElementShape::Wedge6: return SolidElement::C3D6;
    case ElementShape::Wedge15: break;
  }
  return SolidElement::C3D15;
}
}

double meshVolume(vtkUnstructuredGrid* grid, const mlsdeform::PointList& points, const std::vector<char>& selected,
  mlsdeform::PointList* gradient)
{
  using mlsdeform::Vec3;
  mlsdeform::SolidMesh elements;
  std::vector<vtkIdType> others; // the cells measured by their faces
  std::vector<int> nodes;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const int type = grid->GetCellType(c);
    if ((!selected.empty() && !selected[static_cast<std::size_t>(c)]) || cellDimension(type) != 3)
    {
      continue;
    }
    if (const std::optional<mlsdeform::ElementShape> shape = elementShape(type))
    {
      vtkIdType n = 0;
      const vtkIdType* ids = nullptr;
      grid->GetCellPoints(c, n, ids);
      nodes.assign(ids, ids + n);
      elements.add(solidElement(*shape), nodes.data(), 0);
    }
    else
    {
      others.push_back(c);
    }
  }
  mlsdeform::PointList elementGradient;
  double volume = elements.elements() ? mlsdeform::meshVolume(elements, points, { 1.0 }, gradient ? &elementGradient : nullptr) : 0.0;
  if (gradient && !elementGradient.empty())
  {
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      (*gradient)[i] += elementGradient[i];
    }
  }
  if (others.empty())
  {
    return volume;
  }
  // V = sum_f |S_f . (C_f - C_est)| / 3 per cell (FaceQuality.h), its adjoint face by face
  const mlsdeform::CellFaceList faces = cellFaces(grid); // indexed by cell id
  std::vector<mlsdeform::FaceGeometry> geometry;
  std::vector<Vec3> centreBar, areaBar;
  for (const vtkIdType c : others)
  {
    const long first = faces.firstFace(static_cast<int>(c)), last = faces.firstFace(static_cast<int>(c) + 1);
    geometry.clear();
    for (long f = first; f < last; ++f)
    {
      geometry.push_back(mlsdeform::faceGeometry(points, faces.face(f), faces.faceSize(f)));
    }
    volume += mlsdeform::cellGeometry(geometry).volume;
    if (gradient)
    {
      centreBar.assign(geometry.size(), Vec3::Zero());
      areaBar.assign(geometry.size(), Vec3::Zero());
      mlsdeform::addCellGeometryAdjoint(geometry, Vec3::Zero(), 1.0, centreBar, areaBar);
      for (long f = first; f < last; ++f)
      {
        mlsdeform::addFaceGeometryAdjoint(points, faces.face(f), faces.faceSize(f), centreBar[f - first], areaBar[f - first], *gradient);
      }
    }
  }
  return volume;
}
} // namespace mlsvtk
