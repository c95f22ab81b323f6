/**
 * @class vtkSubspaceDeformFilter
 * @brief Common part of the deformation filters: regions, weights, constraints and the solve.
 *
 * A subspace deformation d(x) = sum_j w_j phi_j(x) minimizes StretchWeight * E_stretch +
 * BendWeight * E_bend + FixWeight * E_fix (+ ConstraintWeight * E_constr with geometric
 * constraints, section 6), with E_fix measuring how well the Regions inputs (vtkConstraintRegion
 * outputs) reach their prescribed displacements (paper eq. 10, 11, 14, 17). Subclasses choose the
 * shape functions and how the energies are discretized: vtkMLSDeformFilter (MLS space
 * deformation, sections 4-5) and vtkShellDeformFilter (the mesh-based ground truth, section 3).
 *
 * Inputs: port 0 a vtkPointSet or composite of point sets; port 1 (repeatable) the regions.
 *
 * Output: the input's structure and types, points moved by d(x), point array "Displacement", and
 * field data NumberOfSamples (k), NumberOfIntegrationPoints (N), SetupTime and SolveTime (s),
 * HandleResidual and FixedResidual (the largest, over the regions of that role, of the RMS
 * distance of the region's output points from their targets), TargetCorrection (ExactTargets), ReciprocalCondition, Resampled and
 * Refactorized (whether this update rebuilt the subspace or refactorized), and per constraint
 * region its type, points, residual, iterations and convergence. With MeshQuality on and volume
 * cells in the input (unstructured grids), the mesh quality of paper section 7.3 before and after
 * (vtkDeformationQuality's measures, as OpenFOAM's checkMesh defines them: inverted cells by the
 * face-pyramid check, non-orthogonality and skewness), over every block: InvertedCells, MaxNonOrthogonality (degrees), MaxSkewness and the
 * same prefixed "Original", so that a script can reject a variant before running a solver.
 *
 * Set-up is cached and tracked exactly: property values are compared as they are, input data by
 * VTK's modification times (and, where new data may hold the same values, by the values). Each
 * step (sampling, Phi at the points, regions, constraints, factorization) is redone only when
 * what it depends on changed; when only a handle's motion changes, the update is a right-hand
 * side, a back-substitution and a sparse product at the points, written into the output arrays
 * of the previous update when no one else holds them.
 *
 * Split over MPI processes (pvbatch or pvserver under mpiexec), every process gathers the same
 * regions (their positions from all processes, sorted, each once: GatheredPositions.h), samples
 * the whole domain together with the others (Sampling.h) and so holds the same samples,
 * factorization and coefficients w; it evaluates d(x) at its own points only. The result is the
 * one-process result (the same for any split), a point held by two pieces moves alike in both,
 * and the field data's figures are global. What a process finds wrong in its own piece stops
 * every process with the message. Shell Deform and the SurfaceVertices energies need the whole
 * mesh and run on one process only.
 *
 * Design sensitivities (for gradient-based design optimization): the Handle regions' design
 * variables (vtkConstraintRegion::AddDesignVariable) are listed in field data
 * DesignVariableNames, DesignVariableValues and DesignVariableBounds. With ComputeSensitivities
 * on, the output carries per variable p the point array "dX/d<p>", the exact derivative of the
 * output points; with ObjectiveGradientArray naming a 3-component point array dJ/dX of the input,
 * field data ObjectiveSensitivity holds dJ/dp per variable (reverse mode) and SensitivityMethod
 * says how both were computed (Session/DesignSensitivities.h). The same from a script, on the
 * last update's state without running the pipeline: GetDeformedPoints,
 * ComputeSensitivityProduct and ComputeObjectiveSensitivity (the Python package mlsdeform wraps
 * them). Under MPI these are collective: call them on every process (pvbatch --symmetric).
 *
 * Errors (bad input, a singular system, a cancelled set-up) follow the plugin's one convention
 * (Adapters/FailurePolicy.h): the output is the unchanged input with the field data string
 * "DeformationError" holding the message, the message is in the output window, GetErrorCode() is
 * vtkErrorCode::UserError (NoError after a success), and the request itself succeeds, so that a
 * pipeline (ParaView's among them) updates normally once the input is fixed. Setting
 * AbortExecute (ParaView's progress bar's cancel) stops the set-up within its current stage (on
 * one process; under MPI between stages) and leaves the previous update's output, if any; the
 * next update continues from the last finished stage (Session/DeformationSession.h).
 */
#ifndef vtkSubspaceDeformFilter_h
#define vtkSubspaceDeformFilter_h

#include "MLSDeformFiltersModule.h"
#include "vtkPassInputTypeAlgorithm.h"

#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkDoubleArray;
class vtkIdTypeArray;
class vtkPointSet;
class vtkFieldData;
namespace mlsdeform
{
class Collective;
class SpaceDeformation;
}
namespace mlsvtk
{
class DeformationSession;
struct SubspaceDependencies;
}

class MLSDEFORMFILTERS_EXPORT vtkSubspaceDeformFilter : public vtkPassInputTypeAlgorithm
{
public:
  vtkTypeMacro(vtkSubspaceDeformFilter, vtkPassInputTypeAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// gamma_s, weight of the stretching energy (eq. 12; default 0).
  vtkSetClampMacro(StretchWeight, double, 0.0, 1e9);
  vtkGetMacro(StretchWeight, double);
  ///@}

  ///@{
  /// gamma_b, weight of the bending energy (eq. 13; default 1).
  vtkSetClampMacro(BendWeight, double, 0.0, 1e9);
  vtkGetMacro(BendWeight, double);
  ///@}

  ///@{
  /// gamma_f, weight of the handle and fixed targets (eq. 14; default 1000).
  vtkSetClampMacro(FixWeight, double, 0.0, 1e12);
  vtkGetMacro(FixWeight, double);
  ///@}

  ///@{
  /// gamma_c, weight of the geometric constraints of the Regions inputs (eq. 17; default 10).
  vtkSetClampMacro(ConstraintWeight, double, 0.0, 1e9);
  vtkGetMacro(ConstraintWeight, double);
  ///@}

  ///@{
  /// Handle and Fixed regions reach their targets exactly (default on): the subspace's
  /// least-squares solution (eq. 14) leaves a residual at each target (1-3% of a handle's motion on
  /// CFD cases at the default FixWeight), which a correction field adds back, faded out over
  /// TargetBlendRadius (Core/Basis/ResidualBlend.h). Off: the paper's penalty solution. Field
  /// data TargetCorrection holds the largest residual made up.
  vtkSetMacro(ExactTargets, vtkTypeBool);
  vtkGetMacro(ExactTargets, vtkTypeBool);
  vtkBooleanMacro(ExactTargets, vtkTypeBool);
  ///@}

  ///@{
  /// The Planarity, Circularity, Cylinder, FeatureLine and Rigid regions hold exactly (default
  /// on, with ExactTargets): from the soft solution of section 6, alternating projections find
  /// positions on every constraint that keep the targets (Core/Solver/ConstraintIntersection.h),
  /// and the same correction field as the targets' adds them. Slip regions are exact by their
  /// slide. Constraints that contradict each other or the targets are named in the output window
  /// and stay soft. Off: the paper's soft constraints.
  vtkSetMacro(ExactConstraints, vtkTypeBool);
  vtkGetMacro(ExactConstraints, vtkTypeBool);
  vtkBooleanMacro(ExactConstraints, vtkTypeBool);
  ///@}

  ///@{
  /// The distance over which the exact targets' correction fades out, relative to the bounding
  /// box's diagonal (default 0.2): larger is smoother (the correction's gradient is at most 2.1 x
  /// the residual / the radius beyond the interpolation's own) and costs more points to correct.
  vtkSetClampMacro(TargetBlendRadius, double, 1e-6, 10.0);
  vtkGetMacro(TargetBlendRadius, double);
  ///@}

  enum ConstraintFormulations
  {
    Sparse = 0,  // section 6.1: rows x_i - x_p, sparse for any region size
    MeanCentered // eq. 16: rows x_i - mean, dense over a region's samples
  };
  ///@{
  /// How a constraint measures its points (default Sparse).
  vtkSetClampMacro(ConstraintFormulation, int, Sparse, MeanCentered);
  vtkGetMacro(ConstraintFormulation, int);
  ///@}

  ///@{
  /// Local/global iterations at most (default 5000).
  vtkSetClampMacro(MaxIterations, int, 1, 1000000);
  vtkGetMacro(MaxIterations, int);
  ///@}

  ///@{
  /// The constraint iteration stops when its estimated distance from the fixed point, the last
  /// move times rho/(1-rho) with rho the contraction observed so far, is at most Tolerance times
  /// the model's length (default 1e-7).
  vtkSetClampMacro(Tolerance, double, 0.0, 1.0);
  vtkGetMacro(Tolerance, double);
  ///@}

  enum Accelerations
  {
    None = 0, // the plain alternating iteration of the paper
    Anderson  // Anderson acceleration (depth 5) with a residual safeguard
  };
  ///@{
  /// Acceleration of the local/global iteration (default Anderson).
  vtkSetClampMacro(Acceleration, int, None, Anderson);
  vtkGetMacro(Acceleration, int);
  ///@}

  enum ExtrusionAxes
  {
    NoExtrusion = -1, // a 3D deformation
    ExtrudedX = 0,
    ExtrudedY,
    ExtrudedZ
  };
  ///@{
  /// A 2D case extruded along this axis (an OpenFOAM case whose front and back planes are an
  /// `empty` patch): the displacement does not vary along the axis and has no component along it,
  /// so the front and back planes move alike and the mesh stays 2D (Session/Extrusion.h; only
  /// Handle, Fixed and Slip regions then). Default NoExtrusion.
  vtkSetClampMacro(ExtrusionAxis, int, NoExtrusion, ExtrudedZ);
  vtkGetMacro(ExtrusionAxis, int);
  ///@}

  ///@{
  /// Report the volume mesh's quality before and after in the field data (default on; costs a
  /// pass over the cells per update; not while a handle is dragged and only the surface blocks
  /// move: vtkConstraintRegion::Dragging).
  vtkSetMacro(MeshQuality, vtkTypeBool);
  vtkGetMacro(MeshQuality, vtkTypeBool);
  vtkBooleanMacro(MeshQuality, vtkTypeBool);
  ///@}

  /// The mesh quality of an OpenFOAM case's mesh (an input with the reader's field data
  /// CasePath) is measured on the case's own faces (constant/polyMesh: faces, owner, neighbour).
  /// This starts reading them in a background thread, for the next deformation of that case: a
  /// batch calls it before VTK's reader reads the case, so that both read at once. Optional.
  static void PrefetchCaseFaces(const char* casePath);

  ///@{
  /// Add the point array dX/d<p> of every design variable p to the output (default off: each
  /// costs 3 doubles per point and a tangent solve per update).
  vtkSetMacro(ComputeSensitivities, vtkTypeBool);
  vtkGetMacro(ComputeSensitivities, vtkTypeBool);
  vtkBooleanMacro(ComputeSensitivities, vtkTypeBool);
  ///@}

  ///@{
  /// The input's 3-component point array dJ/dX of an objective J (none by default; zero where J
  /// does not depend on a point, a block without it counts as zero): the output's field data
  /// ObjectiveSensitivity holds dJ/dp per design variable. "None" (ParaView's entry for no
  /// array) is none.
  vtkSetStringMacro(ObjectiveGradientArray);
  vtkGetStringMacro(ObjectiveGradientArray);
  ///@}

  ///@{
  /// Design sensitivities of the last successful update, without running the pipeline (for
  /// scripts in optimization loops). Points are this process's output points in output order
  /// (over the blocks as a composite iterator visits them). Each returns false, with the reason in
  /// GetSensitivityError() and the output window, when there is no successful update or the
  /// arguments do not fit; out is then left as it was.
  /// The output points x + d(x) in double precision (n x 3).
  bool GetDeformedPoints(vtkDoubleArray* out);
  /// Forward mode: sum_p seeds[p] dX/dp (seeds: one value per design variable; out: n x 3).
  bool ComputeSensitivityProduct(vtkDoubleArray* seeds, vtkDoubleArray* out);
  /// Reverse mode: dJ/dp per design variable (out) from gradient = dJ/dX (n x 3).
  bool ComputeObjectiveSensitivity(vtkDataArray* gradient, vtkDoubleArray* out);
  /// Reverse mode for m functions at once, their gradients at some points each: function f's
  /// are the entries starts[f] .. starts[f + 1] - 1 (m + 1 values), each a point index (rows,
  /// this process's output points) and its dJ_f/dX (values, 3 components); out gets m tuples of
  /// dJ_f/dp (one component per design variable). One gathering of the points for all.
  bool ComputeObjectiveSensitivities(vtkIdTypeArray* rows, vtkDoubleArray* values, vtkIdTypeArray* starts, vtkDoubleArray* out);
  /// The mesh's quality as one smooth function and its gradient (an optimizer's constraint): the
  /// KS aggregate (max-shifted, weight rho > 0) of checkMesh's non-orthogonality in degrees
  /// (measure 0) over the interior faces or skewness (1) over the interior and boundary faces
  /// of the deformed volume meshes, or of
  /// the least scaled Jacobian (2: -KS of -sj over an FEM mesh's elements' points, least -
  /// ln(N) / rho <= value <= least) (needs MeshQuality on;
  /// Filters/Core/Quality/FaceQualityAggregate.h). value gets the aggregate and the number of
  /// faces or points N (max <= value <= max + ln(N) / rho), rows and gradient (if not null)
  /// d/dX at this process's output points where it is not zero: their indices and values (3 a row).
  bool ComputeMeshQualityAggregate(int measure, double rho, vtkDoubleArray* value, vtkIdTypeArray* rows, vtkDoubleArray* gradient);
  /// The volume of the deformed volume meshes' 3D cells and its gradient, for an optimizer's
  /// constraint on a part's volume or mass (Adapters/MeshVolume.h: the elements as CalculiX
  /// integrates them, other cells as OpenFOAM measures them): of the cells whose cell array
  /// cellSet is not 0 (a deck's element set; empty or null: every cell), summed over the
  /// processes in their order. value gets the volume and the number of cells, rows and gradient
  /// (if not null) dV/dX at this process's output points where it is not zero (the boundary's),
  /// as for ComputeMeshQualityAggregate. Fails when no process has such a cell, or no grid has
  /// the array cellSet.
  bool ComputeMeshVolume(const char* cellSet, vtkDoubleArray* value, vtkIdTypeArray* rows, vtkDoubleArray* gradient);
  /// The volume a closed surface of polygons encloses on the deformed output points and its
  /// gradient, for an optimizer's constraint on a body (Filters/Core/Quality/PolygonSurface.h:
  /// the divergence theorem; positive with the polygons' normals out of the body): polygons has
  /// a tuple per polygon, its points (this process's output points; 3 components: triangles).
  /// With a non-zero axis, the volume of a shape extruded along it whose surface is open at its
  /// front and back (a one-cell thick 2D case): the flux of the in-plane field, its cross-section
  /// times its depth. value gets the sum over the processes in their order and the number of
  /// polygons, rows and gradient (if not null) dV/dX at this process's output points, as for
  /// ComputeMeshQualityAggregate.
  bool ComputeSurfaceVolume(vtkIdTypeArray* polygons, const double axis[3], vtkDoubleArray* value, vtkIdTypeArray* rows,
    vtkDoubleArray* gradient);
  /// The area of the polygons (as ComputeSurfaceVolume's) and its gradient.
  bool ComputeSurfaceArea(vtkIdTypeArray* polygons, vtkDoubleArray* value, vtkIdTypeArray* rows, vtkDoubleArray* gradient);
  const char* GetSensitivityError() { return this->SensitivityError.c_str(); }

  /// Whether the last output holds deformed points: a cancelled update leaves the previous
  /// update's deformation, or the unchanged input when there was none (the GUI says which).
  bool GetOutputDeformed() const { return this->OutputDeformed; }
  ///@}

  /// Connections of the regions.
  void AddRegionConnection(vtkAlgorithmOutput* region) { this->AddInputConnection(1, region); }
  void RemoveAllRegions() { this->SetInputConnection(1, nullptr); }

  ///@{
  /// How often the stages of the set-up ran (for tests of the cache): the subspace (sampling,
  /// shape functions, energies), Phi at the input points, the Handle and Fixed regions, the
  /// constraints, the factorization, and the solves.
  int GetNumberOfSamplings();
  int GetNumberOfPointEvaluations();
  int GetNumberOfTargetSetups();
  int GetNumberOfConstraintSetups();
  int GetNumberOfFactorizations();
  int GetNumberOfSolves();
  ///@}

protected:
  /// ports: 0 the input, 1 the regions, then optional polydata inputs of the subclass
  explicit vtkSubspaceDeformFilter(int numberOfInputPorts);
  ~vtkSubspaceDeformFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// What the subspace depends on (MLSGeometry.h): it is rebuilt when that changes.
  virtual mlsvtk::SubspaceDependencies GetSubspaceDependencies(vtkInformationVector** inputVector) = 0;
  /// The shape functions and energies for the input (throws mlsdeform exceptions on bad input);
  /// progress from 0 to 0.6.
  virtual std::unique_ptr<mlsdeform::SpaceDeformation> BuildSubspace(
    const std::vector<vtkPointSet*>& inputs, vtkInformationVector** inputVector) = 0;

  double StretchWeight = 0.0;
  double BendWeight = 1.0;
  double FixWeight = 1000.0;
  double ConstraintWeight = 10.0;
  vtkTypeBool ExactTargets = 1;
  double TargetBlendRadius = 0.2;
  vtkTypeBool ExactConstraints = 1;
  int ConstraintFormulation = Sparse;
  int MaxIterations = 5000;
  double Tolerance = 1e-7;
  int Acceleration = Anderson;
  int ExtrusionAxis = NoExtrusion;
  vtkTypeBool MeshQuality = 1;
  vtkTypeBool ComputeSensitivities = 0;
  char* ObjectiveGradientArray = nullptr;

private:
  vtkSubspaceDeformFilter(const vtkSubspaceDeformFilter&) = delete;
  void operator=(const vtkSubspaceDeformFilter&) = delete;

  std::unique_ptr<mlsvtk::DeformationSession> Session;
  struct MeshVolumes; // ComputeMeshVolume's cells and faces, found once per mesh and cell set
  std::unique_ptr<MeshVolumes> Volumes;
  struct MeasuredSurfaces; // ComputeSurfaceVolume's and ComputeSurfaceArea's last polygon arrays
  std::unique_ptr<MeasuredSurfaces> Surfaces;
  /// measure(surface, points, gradient) of the polygons, summed over the processes, into value,
  /// rows and gradient (ComputeSurfaceVolume's and ComputeSurfaceArea's convention); fails with
  /// problem when it is not empty.
  template <typename Measure>
  bool ComputeSurfaceMeasure(const std::string& problem, const char* name, vtkIdTypeArray* polygons, vtkDoubleArray* value, vtkIdTypeArray* rows,
    vtkDoubleArray* gradient, Measure measure);
  /// The design table, the dX/dp arrays (on the moving sets) and dJ/dp of this update into the output.
  void WriteSensitivities(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets,
    const std::vector<char>& moving, vtkFieldData* field, const mlsdeform::Collective& group);
  bool SessionSolved = false; // the last update succeeded: the session's state is the output's
  bool OutputDeformed = false; // the last output holds deformed points (a cancel leaves them)
  std::string SensitivityError;
  /// Runs a sensitivity request: false with the message on a failure or without a solved session.
  template <typename Request>
  bool RunSensitivityRequest(Request request);
};

#endif
