// The volume-mesh measures of paper section 7.3 on a VTK unstructured grid: the scaled Jacobian
// per cell (ElementJacobian.h: linear and quadratic tetrahedra, hexahedra and wedges at their
// corners and integration points; verdict's for pyramids), and as OpenFOAM's checkMesh defines
// them (FaceQuality.h) the inverted cells (a face pyramid of negative volume; a quadratic element
// also where det J <= 0 at one of its points) and the non-orthogonality and skewness per interior
// face. Shared by vtkDeformationQuality and by the deformation filters, which report a summary in
// their output's field data.
#pragma once

#include "Quality/ElementJacobian.h"
#include "Quality/FaceQuality.h"
#include "Quality/FaceQualityAggregate.h"

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

class vtkUnstructuredGrid;

namespace mlsvtk
{
/// The faces of every 3D cell as point-id polygons (none for other cells, nor for another
/// process's cells held as ghosts, VTK's DUPLICATECELL: they are measured there).
mlsdeform::CellFaceList cellFaces(vtkUnstructuredGrid* grid);

/// The element shape of a VTK cell type that ElementJacobian measures, if it is one.
std::optional<mlsdeform::ElementShape> elementShape(int vtkCellType);

/// The scaled Jacobian of (linear and quadratic) tetrahedra, hexahedra and wedges (ElementJacobian)
/// and pyramids (verdict's); NaN for other cells.
std::vector<double> scaledJacobians(vtkUnstructuredGrid* grid);

/// Which elements a verdict measures by their Jacobian: every one (an FEM solver's), or the
/// quadratic ones only (checkMesh's, where face pyramids do not see a midside node folded
/// between its corners; a finite-volume mesh has none and costs nothing).
enum class ElementSet
{
  All,
  Quadratic,
};

/// The cells ElementJacobian measures (of `set`), with their point ids, measured on any points.
class Elements
{
public:
  Elements(vtkUnstructuredGrid* grid, ElementSet set);
  bool empty() const { return Cells.empty(); }
  /// The least scaled Jacobian over the elements (infinity when there are none), and for each
  /// element with det J <= 0 at one of its points inverted[its cell] set to 1.
  double measure(const mlsdeform::PointList& points, std::vector<unsigned char>& inverted) const;
  /// The KS aggregate's part of -sj over every element's points (ElementJacobian's
  /// scaledJacobians: -KS is a smooth lower bound of the least), kept for the gradient.
  mlsdeform::AggregatePart aggregatePart(const mlsdeform::PointList& points, double rho);
  /// Adds d(KS)/dX of the last aggregatePart (the weights of whole) to gradient.
  void addAggregateGradient(const mlsdeform::PointList& points, double rho, const mlsdeform::AggregatePart& whole,
    mlsdeform::PointList& gradient) const;

private:
  std::vector<double> Negated;          // -sj of every element's points, element after element
  std::vector<std::size_t> FrameStart;  // per element, its first entry of Negated (and the end)
  std::size_t CellCount;
  std::vector<int> Cells;
  std::vector<mlsdeform::ElementShape> Shapes;
  std::vector<std::size_t> Start; // Cells.size() + 1 offsets into Points
  std::vector<int> Points;
};

/// The grid's points (throws InvalidInputException when one is not finite), into out or returned.
void gridPoints(vtkUnstructuredGrid* grid, const char* what, mlsdeform::PointList& out);
mlsdeform::PointList gridPoints(vtkUnstructuredGrid* grid, const char* what);

/// Inverted cells (a face pyramid of negative volume), the largest non-orthogonality (degrees) over
/// the interior faces and skewness over the interior and boundary faces.
struct QualitySummary
{
  long inverted = 0;
  double maxNonOrthogonality = 0;
  double maxSkewness = 0;
  double minScaledJacobian = std::numeric_limits<double>::infinity(); // the FEM verdict's (else infinity)
  bool faceMeasures = false; // whether the non-orthogonality and skewness were measured

  /// Adds another mesh's: the counts add up, the largest (least) values stay.
  void add(const QualitySummary& other)
  {
    inverted += other.inverted;
    minScaledJacobian = minScaledJacobian < other.minScaledJacobian ? minScaledJacobian : other.minScaledJacobian;
    faceMeasures = faceMeasures || other.faceMeasures;
    maxNonOrthogonality = maxNonOrthogonality > other.maxNonOrthogonality ? maxNonOrthogonality : other.maxNonOrthogonality;
    maxSkewness = maxSkewness > other.maxSkewness ? maxSkewness : other.maxSkewness;
  }
};

/// Whose verdict a mesh gets: OpenFOAM checkMesh's (face pyramids, non-orthogonality, skewness;
/// quadratic elements also by their Jacobian), or an FEM solver's (every element by its Jacobian
/// at its corners and integration points, no face measures): a solver's mesh file's.
enum class QualityVerdict
{
  CheckMesh,
  FemSolver,
};

/// A grid's interior faces, oriented out of their owner on the rest points (OpenFOAM's face
/// order), its boundary faces, and its elements, measured again for every new set of points of
/// the same cells.
class VolumeMeshQuality
{
public:
  /// The faces of rest's cells, matched by their points (meshFaces); or, when rest is the mesh
  /// of the OpenFOAM case folder casePath as it numbers it, the case's own (caseFaces), with the
  /// figures of the case's points when those are rest's. The FEM solver's verdict needs no faces.
  /// Faces where pieces of the mesh touch (unmerged points, another block or process) are
  /// boundary faces until leaveOutBoundaryFaces.
  explicit VolumeMeshQuality(vtkUnstructuredGrid* rest, const std::string& casePath = std::string(),
    QualityVerdict verdict = QualityVerdict::CheckMesh);

  /// Whether the grid has 3D cells to measure.
  bool hasCells() const { return Has3DCells; }

  /// The position keys of the boundary faces on the rest points (boundaryKeys); and leaving out
  /// those in `between` (sorted: the faces where this grid touches another piece of the mesh, a
  /// block or a process's), with the rest grid's summary measured again when there were some.
  /// Both before the first summary (they use the rest points).
  std::vector<std::uint64_t> boundaryKeys() const;
  void leaveOutBoundaryFaces(const std::vector<std::uint64_t>& between);

  /// The summary of the rest grid, measured with its faces' orientation.
  const QualitySummary& original() const { return Original; }

  /// The summary of grid (the rest grid's cells, any points), measured in buffers kept for the
  /// next call: a new deformation allocates nothing.
  QualitySummary summary(vtkUnstructuredGrid* grid);

  /// Whether the mesh gets checkMesh's face measures (not an FEM solver's verdict).
  bool hasFaceMeasures() const { return Verdict == QualityVerdict::CheckMesh && Has3DCells; }
  /// Whether it gets an FEM solver's verdict (its elements' scaled Jacobian), and those elements.
  bool hasElementMeasures() const { return Verdict == QualityVerdict::FemSolver && Has3DCells; }
  Elements& elements() { return JacobianElements; }

  /// The KS aggregate's part of a face measure over the faces on these points (the rest grid's
  /// cells, FaceQualityAggregate.h); the faces that weigh in it are kept for the
  /// gradient and for the next call with the same pointsKey (the deformation's number of these
  /// points), measure and rho (a value, then its gradient: one pass over the cells).
  mlsdeform::AggregatePart aggregatePart(const mlsdeform::PointList& points, long pointsKey, mlsdeform::QualityMeasure measure, double rho);
  /// Adds the aggregate's gradient (the weights of whole, the parts of every mesh and process)
  /// at the points of the last aggregatePart to gradient.
  void addAggregateGradient(const mlsdeform::PointList& points, mlsdeform::QualityMeasure measure, double rho,
    const mlsdeform::AggregatePart& whole, mlsdeform::PointList& gradient) const;

  const mlsdeform::MeshFaces& mesh() const { return Mesh; }
  const std::vector<int>& orientation() const { return Orientation; }

private:
  QualitySummary summarizeMeasures();

  mlsdeform::MeshFaces Mesh;
  std::vector<int> Orientation;
  bool Has3DCells = false;
  mlsdeform::PointList Points;
  mlsdeform::FaceWorkspace Work;
  mlsdeform::FaceMeasures Measures;
  mlsdeform::FaceAggregate Tail; // the last aggregate's part and the faces that weigh in it
  long TailKey = -1; // the points' key, measure and rho it was measured with
  mlsdeform::QualityMeasure TailMeasure = mlsdeform::QualityMeasure::NonOrthogonality;
  double TailRho = 0;
  mlsdeform::FaceWorkspace TailWork; // its faces' and cells' geometry (the summary's may be of other points)
  QualitySummary Original;
  Elements JacobianElements;
  QualityVerdict Verdict;
  std::vector<unsigned char> Inverted; // per cell: the faces' verdict, then the elements'
};
} // namespace mlsvtk
