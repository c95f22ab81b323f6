// The mesh-based shell deformation of paper section 3, the ground truth of the comparisons: the
// degrees of freedom are the vertex displacements d_i with piecewise linear shape functions
// psi_i (eq. 5), and the energies use the discrete operators of Meyer et al. 2003 ("Discrete
// differential-geometry operators for triangulated 2-manifolds", [27]):
//   E_stretch = sum_t A_t |grad d_t|^2          (eq. 6, per-triangle gradients)
//   E_bend    = sum_i A_i |Lap d_i|^2           (eq. 7, cotangent Laplacian, mixed areas A_i)
// with Lap d_i = 1/(2 A_i) sum_j (cot alpha_ij + cot beta_ij)(d_j - d_i). Like the volumetric
// energies they are divided by their number of rows (T triangles, n vertices) and scaled by the
// model's length l to scale like a squared displacement: sum_t A_t/T |grad d|^2 and
// sum_i A_i l^2/n |Lap d|^2.
#pragma once

#include "Common/KdTree.h"
#include "Common/SamplingDomain.h"
#include "Basis/ShapeFunctions.h"
#include "Basis/SubspaceOperators.h"

namespace mlsdeform
{
/// Meyer's mixed (Voronoi where possible) vertex areas A_i; they sum to the mesh's area.
std::vector<double> mixedAreas(const SamplingDomain& mesh);

/// G (3T x n) and L (n x n) of eq. 9 for the vertex displacements of the mesh's triangles (its
/// tetrahedra are ignored), normalized as above.
/// Triangles of zero area contribute nothing. Throws InvalidInputException for an empty mesh,
/// non-finite points, indices out of range, or a vertex in no triangle of positive area.
DeformationEnergy shellEnergy(const SamplingDomain& mesh);

/// Eq. 11: the same shell energy for the displacements d = Phi w of a subspace, Phi its shape
/// functions at the mesh's vertices: G Phi and L Phi (the vertex-based discretization of the
/// section 4 comparisons), with a ridge of 1e-9 for the combinations that move no vertex.
/// Throws InvalidInputException when a vertex lies outside every support.
DeformationEnergy surfaceVertexEnergy(const ShapeFunctions& basis, const SamplingDomain& mesh);

/// The piecewise linear shape functions psi_i of eq. 5 evaluated at the mesh's vertices:
/// psi_i(x_j) = delta_ij. A position that is not a vertex (farther than 1e-9 l from every
/// vertex) is outside; derivatives are not defined pointwise (the energies come from
/// shellEnergy), so asking for them is a logic error.
class PiecewiseLinearBasis : public ShapeFunctions
{
public:
  explicit PiecewiseLinearBasis(const PointList& vertices);
  void evaluate(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const override;
  std::size_t size() const override { return Vertices.size(); }

private:
  PointList Vertices;
  KdTree Tree;
  double Tolerance = 0;
};
} // namespace mlsdeform
