/**
 * @class vtkMLSSampler
 * @brief Places MLS samples and integration points for a space deformation.
 *
 * Paper Fig. 2 and section 5: dense random samples are drawn on the surface (2D cells; for a
 * volume mesh without 2D cells, the boundary of its 3D cells; for a point cloud, the points) and
 * in the volume (3D cells). Farthest-point selection picks NumberOfSurfaceSamples on the surface,
 * then NumberOfVolumeSamples in the volume away from them; a combined Lloyd relaxation, where a
 * surface sample weighs SurfaceWeight times a volume one, evens them out. Integration points are
 * placed the same way, IntegrationPointRatio times as many. Support radii make every sampled
 * position lie in at least Cover supports.
 *
 * With FollowMeshGrading (the default) the sample density follows the mesh's element density:
 * every triangle and tetrahedron draws as many dense samples, and the farthest-point selection
 * measures distances in units of the local element size (sqrt of a triangle's area, cube root of
 * a tetrahedron's volume). A graded CFD mesh is then sampled densely where it is fine (at the body)
 * and sparsely in its far field; volumes of integration points stay true volumes. Off: samples
 * are uniform in area and volume.
 *
 * A surface-only input has no volume cells: then the embedding space around it is sampled, the
 * input's bounding box enlarged on every side by BoundsPadding times its diagonal.
 *
 * Input: a vtkPointSet or a composite dataset of point sets (all leaves are sampled together).
 * Output port 0: the MLS samples (centers) as vertices, with point arrays "SupportRadius" and
 * "OnSurface" (1 for surface samples). Output port 1: the integration points, with point array
 * "Volume" (their approximate Voronoi volume within the sampled space).
 */
#ifndef vtkMLSSampler_h
#define vtkMLSSampler_h

#include "Adapters/SamplingProperties.h"
#include "MLSDeformFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

class MLSDEFORMFILTERS_EXPORT vtkMLSSampler : public vtkPolyDataAlgorithm
{
public:
  static vtkMLSSampler* New();
  vtkTypeMacro(vtkMLSSampler, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Number of MLS samples placed on the surface (default 800).
  vtkSetClampMacro(NumberOfSurfaceSamples, int, 0, 10000000);
  vtkGetMacro(NumberOfSurfaceSamples, int);
  ///@}

  ///@{
  /// Number of MLS samples placed in the volume (default 200).
  vtkSetClampMacro(NumberOfVolumeSamples, int, 0, 10000000);
  vtkGetMacro(NumberOfVolumeSamples, int);
  ///@}

  mlsSamplingPropertiesMacro();

  ///@{
  /// Weight of a dense surface sample relative to a volume one in the Lloyd step (default 10).
  vtkSetClampMacro(SurfaceWeight, double, 1.0, 1000.0);
  vtkGetMacro(SurfaceWeight, double);
  ///@}

  ///@{
  /// Dense random samples per placed sample or integration point (default 10).
  vtkSetClampMacro(DenseSamplesPerSample, int, 1, 1000);
  vtkGetMacro(DenseSamplesPerSample, int);
  ///@}

  ///@{
  /// For input without volume cells: padding of the sampled box, as a fraction of the bounding-box
  /// diagonal (default 0.1).
  vtkSetClampMacro(BoundsPadding, double, 0.0, 10.0);
  vtkGetMacro(BoundsPadding, double);
  ///@}

protected:
  vtkMLSSampler();
  ~vtkMLSSampler() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int NumberOfSurfaceSamples = 800;
  int NumberOfVolumeSamples = 200;
  double SurfaceWeight = 10.0;
  int DenseSamplesPerSample = 10;
  double BoundsPadding = 0.1;

private:
  vtkMLSSampler(const vtkMLSSampler&) = delete;
  void operator=(const vtkMLSSampler&) = delete;
};

#endif
