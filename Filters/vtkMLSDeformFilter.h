/**
 * @class vtkMLSDeformFilter
 * @brief Moving-least-squares space deformation of point sets driven by handle and fixed regions.
 *
 * Paper sections 4 and 5: the displacement d(x) = sum_j w_j phi_j(x) of the MLS subspace minimizes
 * StretchWeight * E_stretch + BendWeight * E_bend + FixWeight * E_fix (eq. 12-14), with the
 * energies integrated at volumetric integration points and E_fix measuring how well the Regions
 * inputs (vtkConstraintRegion outputs with role Handle or Fixed) reach their prescribed
 * displacements. Every point of every block of the input is moved by the same d(x), so a surface
 * and a volume mesh sharing points stay consistent.
 *
 * Each term is divided by its number of points (regions) or integration points (energies), as
 * section 7 prescribes, and scaled by the model's length so that the weights mean the same for
 * any model size: targets (FixWeight ~ 1000) come first, smoothness (~ 1) last. A stretching weight of at least 1e-6 * BendWeight is always
 * used: it picks, among equally bent results, the least stretched one (pure bending alone does not
 * determine motions normal to a flat configuration).
 *
 * Inputs: port 0 a vtkPointSet or composite of point sets; port 1 (repeatable) the regions;
 * optional port 2 MLS samples and port 3 integration points from vtkMLSSampler (without them the
 * filter samples its input with NumberOfSamples, VolumeSampleFraction, IntegrationPointRatio,
 * LloydIterations, Cover and RandomSeed).
 *
 * Output: the input's structure and types, points moved by d(x), point array "Displacement", and
 * field data NumberOfSamples (k), NumberOfIntegrationPoints (N), SetupTime and SolveTime (s),
 * HandleResidual and FixedResidual (the largest, over the regions of that role, of the RMS
 * distance of the region's points from their targets),
 * ReciprocalCondition, Resampled and Refactorized (whether this update redid those steps).
 *
 * Set-up is cached: when only a handle's motion changes, the update is a right-hand side, a
 * back-substitution and a sparse product at the points.
 */
#ifndef vtkMLSDeformFilter_h
#define vtkMLSDeformFilter_h

#include "MLSDeformFiltersModule.h"
#include "vtkPassInputTypeAlgorithm.h"

class MLSDEFORMFILTERS_EXPORT vtkMLSDeformFilter : public vtkPassInputTypeAlgorithm
{
public:
  static vtkMLSDeformFilter* New();
  vtkTypeMacro(vtkMLSDeformFilter, vtkPassInputTypeAlgorithm);
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
  /// The iteration stops when no constrained point moved more than Tolerance times the model's
  /// length in one iteration (default 1e-7).
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

  ///@{
  /// Internal sampling: number of MLS samples k (default 1000).
  vtkSetClampMacro(NumberOfSamples, int, 4, 10000000);
  vtkGetMacro(NumberOfSamples, int);
  ///@}

  ///@{
  /// Internal sampling: fraction of the samples placed in the volume (default 0.25).
  vtkSetClampMacro(VolumeSampleFraction, double, 0.0, 1.0);
  vtkGetMacro(VolumeSampleFraction, double);
  ///@}

  ///@{
  /// Internal sampling: integration points per sample, N / k (default 4).
  vtkSetClampMacro(IntegrationPointRatio, double, 1.0, 100.0);
  vtkGetMacro(IntegrationPointRatio, double);
  ///@}

  ///@{
  /// Internal sampling: Lloyd relaxation steps (default 5).
  vtkSetClampMacro(LloydIterations, int, 0, 1000);
  vtkGetMacro(LloydIterations, int);
  ///@}

  ///@{
  /// Internal sampling: cover s, the least number of supports covering a position (default 5).
  vtkSetClampMacro(Cover, double, 4.0, 100.0);
  vtkGetMacro(Cover, double);
  ///@}

  ///@{
  /// Internal sampling: random seed (default 0).
  vtkSetClampMacro(RandomSeed, int, 0, VTK_INT_MAX);
  vtkGetMacro(RandomSeed, int);
  ///@}

  /// Connections of the optional inputs.
  void AddRegionConnection(vtkAlgorithmOutput* region) { this->AddInputConnection(1, region); }
  void RemoveAllRegions() { this->SetInputConnection(1, nullptr); }
  void SetSamplesConnection(vtkAlgorithmOutput* samples) { this->SetInputConnection(2, samples); }
  void SetIntegrationPointsConnection(vtkAlgorithmOutput* points) { this->SetInputConnection(3, points); }

  ///@{
  /// How often the expensive steps ran (for tests of the cache).
  vtkGetMacro(NumberOfSamplings, int);
  vtkGetMacro(NumberOfFactorizations, int);
  vtkGetMacro(NumberOfSolves, int);
  ///@}

protected:
  vtkMLSDeformFilter();
  ~vtkMLSDeformFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double StretchWeight = 0.0;
  double BendWeight = 1.0;
  double FixWeight = 1000.0;
  double ConstraintWeight = 10.0;
  int ConstraintFormulation = Sparse;
  int MaxIterations = 5000;
  double Tolerance = 1e-7;
  int Acceleration = Anderson;
  int NumberOfSamples = 1000;
  double VolumeSampleFraction = 0.25;
  double IntegrationPointRatio = 4.0;
  int LloydIterations = 5;
  double Cover = 5.0;
  int RandomSeed = 0;

  int NumberOfSamplings = 0;
  int NumberOfFactorizations = 0;
  int NumberOfSolves = 0;

private:
  vtkMLSDeformFilter(const vtkMLSDeformFilter&) = delete;
  void operator=(const vtkMLSDeformFilter&) = delete;

  struct Cache;
  Cache* Cached;
};

#endif
