// The volume-mesh measures of paper section 7.3 on a VTK unstructured grid: verdict's scaled
// Jacobian per cell, and as OpenFOAM's checkMesh defines them (FaceQuality.h) the inverted cells
// (a face pyramid of negative volume) and the non-orthogonality and skewness per interior face. Shared by vtkDeformationQuality and by the deformation filters,
// which report a summary in their output's field data.
#pragma once

#include "Quality/FaceQuality.h"

#include <string>

class vtkUnstructuredGrid;

namespace mlsvtk
{
/// The faces of every 3D cell as point-id polygons (none for other cells).
mlsdeform::CellFaceList cellFaces(vtkUnstructuredGrid* grid);

/// Verdict's scaled Jacobian of tetrahedra, hexahedra, wedges and pyramids; NaN for other cells.
std::vector<double> scaledJacobians(vtkUnstructuredGrid* grid);

/// The grid's points (throws InvalidInputException when one is not finite), into out or returned.
void gridPoints(vtkUnstructuredGrid* grid, const char* what, mlsdeform::PointList& out);
mlsdeform::PointList gridPoints(vtkUnstructuredGrid* grid, const char* what);

/// Inverted cells (a face pyramid of negative volume), and the largest non-orthogonality (degrees) and skewness
/// over the interior faces.
struct QualitySummary
{
  long inverted = 0;
  double maxNonOrthogonality = 0;
  double maxSkewness = 0;

  /// Adds another mesh's: the counts add up, the largest values stay.
  void add(const QualitySummary& other)
  {
    inverted += other.inverted;
    maxNonOrthogonality = maxNonOrthogonality > other.maxNonOrthogonality ? maxNonOrthogonality : other.maxNonOrthogonality;
    maxSkewness = maxSkewness > other.maxSkewness ? maxSkewness : other.maxSkewness;
  }
};

/// A grid's interior faces, oriented out of their owner on the rest points (OpenFOAM's face
/// order), measured again for every new set of points of the same cells.
class VolumeMeshQuality
{
public:
  /// The faces of rest's cells, matched by their points; or, when rest is the mesh of the
  /// OpenFOAM case folder casePath as it numbers it, the case's own (caseFaces), with the
  /// figures of the case's points when those are rest's.
  explicit VolumeMeshQuality(vtkUnstructuredGrid* rest, const std::string& casePath = std::string());

  /// Whether the grid has 3D cells to measure.
  bool hasCells() const { return Has3DCells; }

  /// The summary of the rest grid, measured with its faces' orientation.
  const QualitySummary& original() const { return Original; }

  /// The summary of grid (the rest grid's cells, any points), measured in buffers kept for the
  /// next call: a new deformation allocates nothing.
  QualitySummary summary(vtkUnstructuredGrid* grid);

  const mlsdeform::CellFaceList& cells() const { return Cells; }
  const mlsdeform::InteriorFaces& faces() const { return Faces; }
  const std::vector<int>& orientation() const { return Orientation; }

private:
  QualitySummary summarizeMeasures() const;

  mlsdeform::CellFaceList Cells;
  mlsdeform::InteriorFaces Faces;
  std::vector<int> Orientation;
  bool Has3DCells = false;
  mlsdeform::PointList Points;
  mlsdeform::FaceWorkspace Work;
  mlsdeform::FaceMeasures Measures;
  QualitySummary Original;
};
} // namespace mlsvtk
