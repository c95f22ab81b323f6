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
 * Inputs and outputs as in vtkSubspaceDeformFilter, plus optional port 2 MLS samples and port 3
 * integration points from vtkMLSSampler (without them the filter samples its input with
 * NumberOfSamples, VolumeSampleFraction, IntegrationPointRatio, LloydIterations, Cover and
 * RandomSeed).
 *
 * Basis selects the shape functions compared in section 4: MLS (default), or the radial basis
 * functions Wendland and Gaussian (compact, with the cover rule's support radii) and Biharmonic
 * and Triharmonic (global, with the linear polynomials added). Global bases make Phi and the
 * k x k system dense: memory grows as k^2 and the set-up as n k + k^3, so keep k to a few
 * thousand and the mesh moderate. EnergyDiscretization selects where the energies are
 * integrated: Volumetric (section 5, at the integration points; any input) or SurfaceVertices
 * (section 4, eq. 11: the shell operators of the input's triangles applied to Phi at its
 * vertices; triangle surfaces only, every point on a triangle).
 */
#ifndef vtkMLSDeformFilter_h
#define vtkMLSDeformFilter_h

#include "Adapters/SamplingProperties.h"
#include "vtkSubspaceDeformFilter.h"

class MLSDEFORMFILTERS_EXPORT vtkMLSDeformFilter : public vtkSubspaceDeformFilter
{
public:
  static vtkMLSDeformFilter* New();
  vtkTypeMacro(vtkMLSDeformFilter, vtkSubspaceDeformFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

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

  /// Internal sampling (without the Samples and IntegrationPoints inputs): as MLS Sampler's.
  mlsSamplingPropertiesMacro();

  enum Bases
  {
    MLS = 0,
    Wendland = 1,
    Gaussian = 2,
    Biharmonic = 3,
    Triharmonic = 4
  };
  ///@{
  /// The shape functions (default MLS); see the class description.
  vtkSetClampMacro(Basis, int, MLS, Triharmonic);
  vtkGetMacro(Basis, int);
  ///@}

  enum EnergyDiscretizations
  {
    Volumetric = 0,
    SurfaceVertices = 1
  };
  ///@{
  /// Where the energies are integrated (default Volumetric); see the class description.
  vtkSetClampMacro(EnergyDiscretization, int, Volumetric, SurfaceVertices);
  vtkGetMacro(EnergyDiscretization, int);
  ///@}

  /// Connections of the optional sampling inputs.
  void SetSamplesConnection(vtkAlgorithmOutput* samples) { this->SetInputConnection(2, samples); }
  void SetIntegrationPointsConnection(vtkAlgorithmOutput* points) { this->SetInputConnection(3, points); }

protected:
  vtkMLSDeformFilter();
  ~vtkMLSDeformFilter() override = default;

  mlsvtk::SubspaceDependencies GetSubspaceDependencies(vtkInformationVector** inputVector) override;
  std::unique_ptr<mlsdeform::SpaceDeformation> BuildSubspace(
    const std::vector<vtkPointSet*>& inputs, vtkInformationVector** inputVector) override;

  int NumberOfSamples = 1000;
  double VolumeSampleFraction = 0.25;
  int Basis = MLS;
  int EnergyDiscretization = Volumetric;

private:
  vtkMLSDeformFilter(const vtkMLSDeformFilter&) = delete;
  void operator=(const vtkMLSDeformFilter&) = delete;
};

#endif
