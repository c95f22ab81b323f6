/**
 * @class vtkShellDeformFilter
 * @brief Mesh-based shell deformation of a triangle surface: the paper's ground truth.
 *
 * Paper section 3 (eq. 6-10): the degrees of freedom are the vertex displacements themselves,
 * the stretching energy uses per-triangle gradients and the bending energy the cotangent
 * Laplacian with Meyer et al.'s mixed Voronoi areas. The same Regions inputs, weights and
 * constraints as vtkMLSDeformFilter (see vtkSubspaceDeformFilter), so the two can be compared
 * directly. The system has one unknown per vertex (n x n, sparse), so it suits the comparisons
 * and moderate meshes, not volume meshes: every point must belong to a triangle (polygons are
 * triangulated), and region positions must be vertices of the input.
 */
#ifndef vtkShellDeformFilter_h
#define vtkShellDeformFilter_h

#include "vtkSubspaceDeformFilter.h"

class MLSDEFORMFILTERS_EXPORT vtkShellDeformFilter : public vtkSubspaceDeformFilter
{
public:
  static vtkShellDeformFilter* New();
  vtkTypeMacro(vtkShellDeformFilter, vtkSubspaceDeformFilter);

protected:
  vtkShellDeformFilter();
  ~vtkShellDeformFilter() override = default;

  mlsvtk::SubspaceDependencies GetSubspaceDependencies(vtkInformationVector** inputVector) override;
  std::unique_ptr<mlsdeform::SpaceDeformation> BuildSubspace(
    const std::vector<vtkPointSet*>& inputs, vtkInformationVector** inputVector) override;

private:
  vtkShellDeformFilter(const vtkShellDeformFilter&) = delete;
  void operator=(const vtkShellDeformFilter&) = delete;
};

#endif
