#include "Adapters/VolumeMeshQuality.h"

#include "Adapters/CaseFaces.h"
#include "Adapters/CellFaces.h"
#include "Adapters/MeshCells.h"
#include "Adapters/PointSets.h"
#include "Common/BoundingBox.h"

#include <vtkCell.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkLogger.h>
#include <vtkMeshQuality.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace mlsvtk
{
mlsdeform::CellFaceList cellFaces(vtkUnstructuredGrid* grid)
{
  return mlsdeform::CellFaceList::build(static_cast<int>(grid->GetNumberOfCells()), [&]() {
    // per thread: GetCellPoints' thread-safe variant's list, a face's points
    return [&, scratch = vtkSmartPointer<vtkIdList>::New(), polygon = std::vector<vtkIdType>()](int c, auto add) mutable {
      const int type = grid->GetCellType(c);
      if (type == VTK_POLYHEDRON)
      {
        visitPolyhedronFaces(grid, c, [&](const vtkIdType* face, vtkIdType n) { add(face, static_cast<std::size_t>(n)); });
        return;
      }
      const LocalFaces& local = cellTypeFaces(type);
      vtkIdType n = 0;
      const vtkIdType* points = nullptr;
      if (!local.empty())
      {
        grid->GetCellPoints(c, n, points, scratch);
      }
      for (const std::vector<int>& face : local)
      {
        polygon.resize(face.size());
        for (std::size_t i = 0; i < face.size(); ++i)
        {
          polygon[i] = points[face[i]];
        }
        add(polygon.data(), polygon.size());
      }
    };
  });
}

std::vector<double> scaledJacobians(vtkUnstructuredGrid* grid)
{
  std::vector<double> jacobians(grid->GetNumberOfCells(), std::numeric_limits<double>::quiet_NaN());
  CellsByType byType;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    double (*measure)(vtkCell*) = nullptr; // verdict's scaled Jacobian of the type, if it has one
    switch (grid->GetCellType(c))
    {
      case VTK_TETRA:
        measure = &vtkMeshQuality::TetScaledJacobian;
        break;
      case VTK_HEXAHEDRON:
        measure = &vtkMeshQuality::HexScaledJacobian;
        break;
      case VTK_WEDGE:
        measure = &vtkMeshQuality::WedgeScaledJacobian;
        break;
      case VTK_PYRAMID:
        measure = &vtkMeshQuality::PyramidScaledJacobian;
        break;
      default:
        continue;
    }
    jacobians[c] = measure(byType.get(grid, c)->GetRepresentativeCell());
  }
  return jacobians;
}

void gridPoints(vtkUnstructuredGrid* grid, const char* what, mlsdeform::PointList& out)
{
  out.resize(grid->GetNumberOfPoints());
  copyPoints(grid, out.data());
  mlsdeform::requireFinite(out, what);
}

mlsdeform::PointList gridPoints(vtkUnstructuredGrid* grid, const char* what)
{
  mlsdeform::PointList points;
  gridPoints(grid, what, points);
  return points;
}

VolumeMeshQuality::VolumeMeshQuality(vtkUnstructuredGrid* rest, const std::string& casePath)
{
  std::optional<CaseMesh> own = casePath.empty() ? std::nullopt : caseFaces(casePath, rest);
  if (own)
  {
    Cells = std::move(own->faces.cells);
    Faces = std::move(own->faces.interior);
  }
  else
  {
    vtkLogScopeF(TRACE, "mesh quality: the cells' faces");
    Cells = cellFaces(rest);
  }
  Has3DCells = Cells.faces() > 0;
  Measures.perFace = false; // the summary's maxima only
  if (Has3DCells)
  {
    if (!own)
    {
      vtkLogScopeF(TRACE, "mesh quality: interior faces");
      Faces = mlsdeform::interiorFaces(Cells);
    }
    vtkLogScopeF(TRACE, "mesh quality: the undeformed mesh's figures");
    gridPoints(rest, "the mesh's points", Points);
    if (own && own->points == Points)
    {
      vtkLogF(TRACE, "mesh quality: the case's points are the grid's, their figures read with the faces");
      Orientation = std::move(own->orientation);
      Measures = std::move(own->measures);
      Work = std::move(own->work);
    }
    else
    {
      Orientation = mlsdeform::faceOrientation(Points, Cells, Faces, Work, Measures);
    }
    Original = summarizeMeasures();
  }
}

QualitySummary VolumeMeshQuality::summary(vtkUnstructuredGrid* grid)
{
  gridPoints(grid, "the mesh's points", Points);
  mlsdeform::faceMeasures(Points, Cells, Faces, Orientation, Work, Measures);
  return summarizeMeasures();
}

QualitySummary VolumeMeshQuality::summarizeMeasures() const
{
  return QualitySummary{ Measures.invertedCells, Measures.maxNonOrthogonality, Measures.maxSkewness };
}
} // namespace mlsvtk
