// The cached state of a deformation between updates (libigl's precompute/solve split; VTK's
// MTimes say what changed): what was read from the inputs, the subspace, Phi at the points, the
// target regions, the constraints, the factorization and the output arrays. One method per stage,
// each with its own key; a stage runs again only when its key changed or an earlier stage it
// depends on ran again:
//
//   stage                  key                                          invalidates
//   0 readInputs           point and region stamps -> values' versions  (versions feed the keys below)
//   1 updateSubspace       SubspaceKey: subclass's dependencies,        2, 3, 4, 5
//                          cells and points (if it samples the input)
//   2 updatePointRows      the points' version                          3 (whose rows view these)
//   3 updateTargets        TargetsKey: (version, role, weight) per      4b, 5
//                          Handle/Fixed region
//   4 updateConstraints    ConstraintsKey: (version, role, weight) per  4b, 5
//                          constraint region, the formulation
//  4b updateExactTargets   the points' version, the target and          -
//                          constraint regions, the blend radius, whether
//                          constraints are exact (ExactTargets.h)
//   5 updateFactorization  the weights (SpaceDeformation knows which    -
//                          weights its factor is for)
//   6 solve, writeOutput   none: every update (a new handle motion costs a right-hand side,
//                          a back-substitution and d = Phi w at the points)
//
// A stage's key is stored only once the stage succeeded, so a failure or a cancel leaves the
// session consistent: the next update redoes what did not finish. Every process of an MPI run
// passes the same stages in the same order (their keys are global), and a cancel on any process
// stops all of them between stages.
#pragma once

#include "Basis/SubspaceOperators.h"
#include "Common/Collective.h"
#include "Session/DeformedOutput.h"
#include "Session/DesignSensitivities.h"
#include "Session/ExactTargets.h"
#include "Session/Extrusion.h"
#include "Session/MeshQualityReport.h"
#include "Session/RegionInputs.h"
#include "Session/SlipPlanes.h"
#include "Session/SubspaceDependencies.h"
#include "Solver/ConstraintIntersection.h"
#include "Solver/SpaceDeformation.h"

#include <functional>
#include <array>
#include <memory>
#include <optional>
#include <vector>

class vtkAlgorithm;
class vtkFieldData;
class vtkInformationVector;
class vtkPointSet;

namespace mlsvtk
{
/// A region as a stage depends on it.
struct RegionKey
{
  long version; // of its gathered positions (and sets)
  int role;
  double weight;
  std::vector<double> parameters; // a Symmetric region's mirror plane (point, normal), a Coplanar or Distance region's group, a Distance axis, an Offset bound
  bool operator==(const RegionKey& o) const { return version == o.version && role == o.role && weight == o.weight && parameters == o.parameters; }
};

/// Stage 1: what the subspace was built from.
struct SubspaceKey
{
  SubspaceDependencies dependencies;
  Stamp cells;       // of the input's cells, when the subspace depends on the geometry
  long points = 0;   // the input points' version, when the subspace depends on the geometry
  bool operator==(const SubspaceKey& o) const { return dependencies == o.dependencies && cells == o.cells && points == o.points; }
};

/// Stage 3: the Handle and Fixed regions.
struct TargetsKey
{
  std::vector<RegionKey> regions;
  bool operator==(const TargetsKey& o) const { return regions == o.regions; }
};

/// Stage 4: the constraint regions and how they are measured.
struct ConstraintsKey
{
  std::vector<RegionKey> regions;
  mlsdeform::ConstraintFormulation formulation;
  bool operator==(const ConstraintsKey& o) const { return regions == o.regions && formulation == o.formulation; }
};

/// Stage 4b: the exact targets' (and constraints') blend over the sites, at the points.
struct ExactTargetsKey
{
  long points = 0;
  TargetsKey targets;
  std::vector<RegionKey> constraints; // none when constraints are not exact
  double radius = 0; // relative to the diagonal; 0: none (the penalty solution)
  bool operator==(const ExactTargetsKey& o) const
  {
    return points == o.points && targets == o.targets && constraints == o.constraints && radius == o.radius;
  }
};

/// A displacement of the points, d = S (Phi w + B r): the subspace's coefficients w and the
/// exact targets' residuals r (empty for the penalty solution).
struct PointField
{
  mlsdeform::Displacements w;
  mlsdeform::PointDisplacements r;
};

/// A stage's key as last built (none: not built, or invalidated).
template <typename Key>
class Stage
{
public:
  bool stale(const Key& key) const { return !Built || !(*Built == key); }
  void built(Key key) { Built = std::move(key); }
  void invalidate() { Built.reset(); }

private:
  std::optional<Key> Built;
};

class DeformationSession
{
public:
  /// owner: the algorithm whose progress is reported and whose AbortExecute cancels the set-up.
  explicit DeformationSession(vtkAlgorithm* owner);

  /// How often each stage ran (the cache's tests read them).
  struct Runs
  {
    int subspace = 0, pointRows = 0, targets = 0, constraints = 0, factorization = 0, solve = 0;
  };
  const Runs& runs() const { return Counts; }

  /// Stage 0: this process's points (read again when their stamp changes, a new version when
  /// their values do or the extrusion axis changed) and the Regions inputs of all processes
  /// (RegionInputs.h), the slip planes fitted again when a region changed. extrusionAxis: 0-2 for
  /// a 2D case extruded along x, y or z (Extrusion.h), -1 for none. Throws InvalidInputException on
  /// bad input (no points on any process, NaN, a region that selects nothing, no Handle, a Slip
  /// region that is no plane).
  void readInputs(const std::vector<vtkPointSet*>& sets, vtkInformationVector* regions, int extrusionAxis,
    const mlsdeform::Collective& group);

  /// Stage 1: the subspace (shape functions and energies), rebuilt by build when its key changed;
  /// returns whether it was (the output's "Resampled").
  bool updateSubspace(const SubspaceDependencies& dependencies, const std::vector<vtkPointSet*>& sets,
    const std::function<std::unique_ptr<mlsdeform::SpaceDeformation>()>& build, const mlsdeform::Collective& group);

  /// Stage 2: Phi at this process's points; throws InvalidInputException for a point outside
  /// every support. Progress from 0.6 to 0.9.
  void updatePointRows(const mlsdeform::Collective& group);

  /// Stage 3: the Handle and Fixed regions' rows of Phi (copied from stage 2's where a region
  /// position is an input point) and their normal matrices.
  void updateTargets();

  /// Stage 4: the geometric constraints (section 6). Throws InvalidInputException for a
  /// constraint other than Slip in an extruded deformation.
  void updateConstraints(mlsdeform::ConstraintFormulation formulation);

  /// Stage 4b: exact targets (ExactTargets.h) with the blend's fade radius R = radius x the
  /// diagonal, and exact constraints when asked (the shape constraints other than Slip, which
  /// the slide keeps exactly); radius 0: the penalty solution of eq. 14 alone. Progress from 0.9
  /// to 0.95.
  void updateExactTargets(double radius, bool exactConstraints, const mlsdeform::Collective& group);

  /// Stage 5: the factorization of eq. 14 (17); returns whether it ran (the output's
  /// "Refactorized"). Throws SolverException for a singular system.
  bool updateFactorization(const mlsdeform::EnergyWeights& weights);

  /// Stage 6: the solve for the targets' prescribed displacements of this update (kept: the
  /// design sensitivities below are those of the last solve). With exact targets, the solution's
  /// rmsResidual is the output's (zero to round-off but where targets at one position disagree),
  /// and so is constraintResidual (the constrained points moved by the correction too).
  mlsdeform::SpaceDeformation::Solution solve(const mlsdeform::IterationSettings& settings, const mlsdeform::Collective& group);
  /// The largest residual the exact targets' blend made up (0 for the penalty solution).
  double targetCorrection() const;
  /// The target regions whose points share positions with other targets that prescribe another
  /// displacement (exact targets meet their mean there): "#c (Role, up to distance), ..." by
  /// Regions input; empty when none.
  const std::string& targetConflicts() const { return TargetConflicts; }
  /// With exact constraints that the targets and the other constraints contradict (the
  /// alternating projections did not meet): the constraint regions with their gaps, "#c (Role,
  /// gap distance), ..."; the output is then the soft solution there. Empty when none.
  const std::string& constraintConflicts() const { return ConstraintConflicts; }

  /// The point sets this update moves: all, but while a region's handle is dragged only the
  /// surface (polydata) sets of an input that has volume sets too (an OpenFOAM case's patches
  /// beside its internal mesh), so that a drag step costs the surface's points only.
  std::vector<char> movingSets(const std::vector<vtkPointSet*>& sets) const;
  /// Whether a region's handle is being dragged (this update moves the surface blocks only).
  bool dragged() const;

  /// x + d(x) and Displacement into the output point sets for the last solve; a set that is not
  /// moving keeps the previous update's (DeformedOutput::write).
  void writeOutput(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets, const std::vector<char>& moving);
  /// The last written points and Displacement into the output point sets again (a cancelled
  /// update leaves the previous output); false when they do not fit these sets.
  bool restoreOutput(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets) { return Output.restore(inSets, outSets); }

  /// The volume mesh's quality before and after, into field (MeshQualityReport.h); casePath: the
  /// OpenFOAM case folder the input was read from, or "".
  void reportQuality(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets, vtkFieldData* field,
    const std::string& casePath, bool femSource, const mlsdeform::Collective& group);
  /// Reads ahead the case's faces that the next reportQuality needs (MeshQualityReport::readAhead).
  void readQualityAhead(const std::vector<vtkPointSet*>& inSets, const std::string& casePath) const
  {
    Quality.readAhead(inSets, casePath);
  }

  /// Design sensitivities of the last solve (DesignSensitivities.h). The design variables of this
  /// update's Handle regions:
  const DesignTable& design() const { return Design; }
  /// Forward mode: the output displacement's derivative along seeds (one per design variable).
  PointField tangent(const std::vector<double>& seeds) const;
  /// S (Phi w + B r) at this process's points [offset, offset + n), into out: the displacement
  /// of the last solve or a derivative (tangent).
  void displacement(const PointField& field, long offset, long n, double* out) const;
  /// The point arrays dX/d<variable> of every design variable into the moving output point sets
  /// (the others keep the previous update's with its points: DeformedOutput::addDerived).
  void writeSensitivities(const std::vector<vtkPointSet*>& outSets, const std::vector<char>& moving);
  /// Reverse mode: dJ/dp per design variable from g = dJ/dX at this process's points (3 values
  /// per point, in order; a collective operation under MPI); method says how it was computed.
  std::vector<double> objectiveSensitivity(const std::vector<double>& gradient, const mlsdeform::Collective& group, std::string& method);
  /// The same for several functions at once, their gradients given at some points each: one
  /// gathering of their points and of Phi's rows there, then per function one back-substitution;
  /// dJ_f/dp per function.
  std::vector<std::vector<double>> objectiveSensitivities(
    SparseGradients gradients, const mlsdeform::Collective& group, std::string& method);
  /// x + d(x) in double precision at this process's points (the output's points before they are
  /// stored in the input's precision) into out (3 per point); and kept, computed once per
  /// solution, for what is measured on them (the mesh quality, the mesh volume).
  void deformedPoints(double* out) const;
  const mlsdeform::PointList& deformedPoints();
  /// The last solution's number (a new one at every solve): what is measured on the deformed
  /// points is keyed by it.
  long solutionNumber() const { return Solutions; }
  /// The KS aggregate of a face measure of the deformed volume meshes and its gradient at the
  /// output points (MeshQualityReport::aggregate; the last update's report).
  MeshQualityReport::Aggregate qualityAggregate(
    mlsdeform::QualityMeasure measure, double rho, const mlsdeform::Collective& group, std::vector<double>* gradient);
  /// This process's input points, concatenated over the point sets.
  const mlsdeform::PointList& inputPoints() const { return Points; }

  const mlsdeform::SpaceDeformation& model() const { return *Model; }
  const std::vector<RegionInput>& regions() const { return Regions; }
  /// The constraint regions the model iterates on, in its order (not an extruded case's front
  /// and back Slip planes, which the extrusion keeps exactly).
  std::vector<const RegionInput*> iteratedConstraints() const;
  /// The diagonal of the bounding box of all processes' points.
  double diagonal() const { return Diagonal; }
  /// Seconds the last set-up (a run of stage 1 or 5) took.
  double setupTime() const { return SetupTime; }
  void setSetupTime(double seconds) { SetupTime = seconds; }

private:
  /// With exact targets: the target regions' residuals of the output (the misses of ExactTargets
  /// per stacked target) and the regions whose targets disagree.
  void measureTargets(const std::vector<mlsdeform::PointDisplacementsView>& prescribed, const std::vector<double>& miss);
  /// With exact targets: the constraint residuals of the output, the correction included.
  void measureConstraints();
  /// The positions on every exact constraint (Solver/ConstraintIntersection.h) reached from the
  /// positions x + Phi w, the target sites kept at x + Phi w + r.
  mlsdeform::IntersectionResult intersect(const mlsdeform::Displacements& w, const mlsdeform::PointDisplacements& r) const;
  /// The constraint regions whose sets the intersection left apart (constraintConflicts).
  void reportConflicts(const mlsdeform::IntersectionResult& z);
  /// r at the constraint sites from an intersection's positions (z - x - Phi w).
  void constraintResiduals(const mlsdeform::IntersectionResult& z, const mlsdeform::Displacements& w, mlsdeform::PointDisplacements& r) const;

  vtkAlgorithm* Owner;
  Runs Counts;
  long NextVersion = 0;

  // stage 0
  Stamp PointsStamp;
  mlsdeform::PointList Points; // the input points of this process, concatenated over the point sets
  long PointsVersion = -1;
  double Diagonal = -1; // -1: not known for these points
  Extrusion Extruded;
  std::vector<RegionInput> Regions;
  Stage<std::vector<RegionKey>> SlipKey;
  std::vector<SlipPlane> Slips;

  // stages 1-5 (the factorization's state is the model's own)
  Stage<SubspaceKey> Subspace;
  std::unique_ptr<mlsdeform::SpaceDeformation> Model;
  Stage<long> PointRowsKey;
  mlsdeform::RowBlocks PointRows;
  Stage<TargetsKey> Targets;
  Stage<ConstraintsKey> Constraints;
  Stage<ExactTargetsKey> ExactKey;
  ExactTargets Exact;
  int ExactBuilds = 0; // the blend's version, for the rows cached below
  mlsdeform::PointList ConstraintPositions; // every constraint set's positions, in the model's order
  std::vector<long> SetBegin;                  // each model set's first row in ConstraintPositions, and the end
  std::vector<char> SetIsSlip;                 // per model set: a Slip set (kept by the slide, no site)
  std::vector<std::vector<long>> SiteSets;     // per model set: its points' sites (empty: no exact constraint)
  struct ConstraintBlendRows // the blend at them, for the output's constraint residuals
  {
    int exactBuild = -1, constraints = -1;
    mlsdeform::GatheredRows rows;
  } ConstraintBlend;
  double SetupTime = 0;

  // stage 6
  std::vector<std::vector<double>> Prescribed; // the targets' displacements of all processes, gathered
  DesignTable Design;
  PrescribedDerivatives Derivatives;
  mlsdeform::SpaceDeformation::Solution Last;
  PointField LastField;
  long Solutions = 0;
  mlsdeform::PointList Deformed; // deformedPoints() of solution DeformedOf
  long DeformedOf = -1;
  // Phi w of the last solve at every point, when the whole output is written (no drag): the
  // exact targets' Phi w at the region positions that are points is read from it rather than
  // multiplied again (a 1M-point sphere's regions' 410k rows doubled its variation), and the
  // output copies it
  mlsdeform::PointDisplacements PointsProduct;
  bool PointsProductIsLast = false;
  std::vector<long> TargetRows; // per region position: its row of PointRows (positionsAmong), or -1
  std::string TargetConflicts;
  std::string ConstraintConflicts;
  bool Intersected = false; // the constraint sites' residuals are an intersection's (exact constraints met)
  // Phi at the gathered positions of the last two gradients' supports (an optimizer's dJ/dX and
  // its constraints' each keep theirs from call to call), for the subspace and points they were
  // evaluated with; the one used last first
  struct GradientRows
  {
    mlsdeform::PointList positions;
    int subspace = -1;
    long points = -1;
    mlsdeform::GatheredRows rows; // views of PointRows' rows where the positions are input points
    int exactBuild = -1;
    mlsdeform::GatheredRows blend; // B there (exact targets)
  };
  PositionOrder PointOrder; // of Points at PointOrderOf (gradients' points are gathered in it)
  long PointOrderOf = -1;
  std::array<GradientRows, 3> Gradients; // an optimizer's objective, its constraints, its mesh quality
  /// Gradients' entry for these positions (among[i]: a point at positions[i], or -1), made first
  /// (evaluated in place of the least recently used if none is).
  const GradientRows& gradientRows(const mlsdeform::PointList& positions, const std::vector<long>& among);
  DeformedOutput Output;
  MeshQualityReport Quality;
};
} // namespace mlsvtk
