/**
 * @class vtkDeformationQuality
 * @brief Volume-mesh quality of a deformed mesh, and of its original, side by side.
 *
 * The measures of paper section 7.3:
 * - per cell the scaled Jacobian of tetrahedra, hexahedra and wedges, linear or quadratic
 *   (ElementJacobian.h: at the corners and the integration points; verdict's on linear cells, with
 *   VTK's wedge orientation) and of pyramids (verdict's): 1 for the ideal element, negative for an
 *   inverted one; NaN for other cell types (polyhedra, 2D cells), which the statistics skip;
 * - per interior face (a face shared by two 3D cells, also of vtkPolyhedron cells) the
 *   non-orthogonality (degrees) and skewness exactly as OpenFOAM's checkMesh defines them. A
 *   face's orientation (out of its owner, the lower cell id) is taken from the original mesh and
 *   kept, as OpenFOAM keeps its face order: a neighbour folded over its owner shows above 90.
 *   A boundary face (of one cell) has checkMesh's skewness too, its owner mirrored across it;
 *   where two pieces of the mesh touch without sharing points (unmerged points, the MPI
 *   processes' pieces) their faces are on no boundary and get no measure here (MLS Deform's
 *   report measures them across the pieces).
 * - per cell whether it is inverted: a face pyramid (apex the cell centre, base a face as the
 *   cell lists it, VTK's outward order) of negative volume, OpenFOAM's face-pyramid check. The
 *   scaled Jacobian is not that test: some warped cells that checkMesh accepts have a negative one.
 *   A quadratic element is also inverted where det J <= 0 at one of its points.
 *
 * Input port 0: the mesh to measure (the deformed one). Input port 1 (optional): the original mesh
 * with the same cells, whose measures are reported alongside.
 * Output port 0: the input with cell arrays ScaledJacobian, MaxNonOrthogonality (over the cell's
 * interior faces; 0 for a cell without any) and MaxSkewness (over its interior and boundary
 * faces) and, with an original, the same arrays prefixed "Original"; field data InvertedCells
 * (and OriginalInvertedCells).
 * Output port 1: the interior faces as polygons, cell arrays NonOrthogonality, Skewness, Owner,
 * Neighbour (and the Original measures).
 * Output port 2: a summary table, one row per measure (ScaledJacobian, NonOrthogonality,
 * Skewness over the interior and boundary faces, InvertedCells) with columns Min, Mean, Max and,
 * with an original, OriginalMin, OriginalMean, OriginalMax. The InvertedCells row holds the
 * number of inverted cells in all
 * three columns.
 */
#ifndef vtkDeformationQuality_h
#define vtkDeformationQuality_h

#include "MLSDeformFiltersModule.h"
#include "vtkUnstructuredGridAlgorithm.h"

class MLSDEFORMFILTERS_EXPORT vtkDeformationQuality : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkDeformationQuality* New();
  vtkTypeMacro(vtkDeformationQuality, vtkUnstructuredGridAlgorithm);

  /// The original (undeformed) mesh; optional.
  void SetOriginalConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetOriginalData(vtkDataObject* data) { this->SetInputData(1, data); }

protected:
  vtkDeformationQuality();
  ~vtkDeformationQuality() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkDeformationQuality(const vtkDeformationQuality&) = delete;
  void operator=(const vtkDeformationQuality&) = delete;
};

#endif
