// The volume mesh's quality before and after the deformation (paper section 7.3, as OpenFOAM's
// checkMesh measures it), over every block and process, into the output's field data: the faces
// and the original's measures are found once per input mesh, the deformed mesh is measured every
// update.
#pragma once

#include "Adapters/Stamp.h"
#include "Adapters/VolumeMeshQuality.h"
#include "Common/Collective.h"
#include "Session/PieceInterfaces.h"

#include <memory>
#include <string>
#include <vector>

class vtkFieldData;
class vtkObject;
class vtkPointSet;

namespace mlsvtk
{
class MeshQualityReport
{
public:
  /// Adds InvertedCells, MaxNonOrthogonality, MaxSkewness and the same prefixed "Original" to
  /// field when some process has volume cells (checkMesh's verdict; quadratic elements are
  /// measured by their Jacobian for InvertedCells only). A structural solver's mesh file (field data
  /// QualityVerdict "FemSolver") gets the FEM solver's verdict instead of checkMesh's: InvertedCells
  /// by the elements' Jacobian, MinScaledJacobian, and no face measures. Split over processes (or
  /// blocks, or cells whose points were not merged), each measures its own piece and the faces
  /// between pieces are measured as interior faces across them (PieceInterfaces); the summaries
  /// are combined exactly: the whole mesh's figures. Cells
  /// it cannot measure give a warning (from owner) once per input mesh and the field data
  /// MeshQualityProblem (why) on every update; the deformation stands.
  /// casePath: the OpenFOAM case folder the input was read from (or ""), whose own faces a grid
  /// that is its mesh is measured on (VolumeMeshQuality). femSource: the input came from a
  /// structural solver's mesh file through a reader that does not say so (femReaderUpstream).
  void report(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets, vtkFieldData* field,
    const std::string& casePath, bool femSource, const mlsdeform::Collective& group, vtkObject* owner);

  /// Starts reading ahead the faces of the OpenFOAM case casePath (CaseFaces.h) for the next
  /// report when that report will find the faces of new cells: they are read in a background
  /// thread while the deformation is set up.
  void readAhead(const std::vector<vtkPointSet*>& inSets, const std::string& casePath) const;

  /// The KS aggregate of a face measure over the faces of every volume mesh on every process
  /// (FaceQualityAggregate.h: the non-orthogonality over the interior faces, the skewness over
  /// the interior and boundary faces; the faces between pieces as interior faces, as in the
  /// report), on `points` (this process's output points, the sets in order, as the last report's
  /// sets), and its gradient there (3 per point) when gradient is given: the aggregate's value
  /// and its number of faces, the same on every process. Throws InvalidInputException when no
  /// mesh of any process has checkMesh's face measures (none measured: MeshQuality off; an FEM
  /// solver's mesh). pointsKey names the points (the deformation's number): the faces' pass is
  /// made once per key, measure and rho (a value, then its gradient).
  struct Aggregate
  {
    double value;
    long count;
  };
  Aggregate aggregate(const mlsdeform::PointList& points, long pointsKey, mlsdeform::QualityMeasure measure, double rho,
    const mlsdeform::Collective& group, std::vector<double>* gradient);

private:
  // The stamp of the cells and points of inSets, to compare with Measured.
  static Stamp stampOf(const std::vector<vtkPointSet*>& inSets);

  Stamp Measured; // of the cells and points the faces and the original's measures come from
  std::string Problem; // why Measured's cells are not measured (field data MeshQualityProblem), or ""
  std::vector<std::unique_ptr<VolumeMeshQuality>> Quality;
  PieceInterfaces Interfaces; // the faces where the sets' and processes' pieces touch
  std::vector<long> Starts; // the first point of each set in the last report's sets (and their end)
  QualitySummary Original;
};
} // namespace mlsvtk
