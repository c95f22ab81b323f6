// The exact discrete shape derivatives of a linear elastic solid, element by element, as the
// adjoint method needs them (issue 65; TACS's addAdjointResXptSensProducts, FEniCS's
// CoordinateDerivative): for K(X) u = f(X) and a response J(u, X) with K lambda = dJ/du,
//   dJ/dX = dJ/dX|_u - lambda^T (d(K u)/dX - df/dX).
// The element's bilinear form, integrated at the solver's points (SolidElements.h),
//   W_e(X; u, lambda) = lambda^T K_e(X) u = sum_g w_g |det J_g| a(grad u, grad lambda),
//   a(G, H) = l tr G tr H + m (G + G^T) : H   (Lame's l and m; sigma(G) : H),
// with grad u = sum_a u_a (x) grad N_a and grad N_a = J^-T dN_a/dxi, has at node b
//   dW_e/dX_b = sum_g w_g |det J_g| (a(grad u, grad lambda) I - A_g) grad N_b,
//   A = l (tr H G^T + tr G H^T) + m (G^T (H + H^T) + H^T (G + G^T)),  G = grad u, H = grad lambda,
// from d|det J|/dX_b = |det J| grad N_b and d(grad N_a)/dX_b = -grad N_b (grad N_a)^T (an
// Eshelby-like tensor; no finite differences). The volume V_e = sum_g w_g |det J_g| has
// dV_e/dX_b = sum_g w_g |det J_g| grad N_b.
#pragma once

#include "Structural/SolidElements.h"

#include <vector>

namespace mlsdeform
{
/// An isotropic linear elastic material.
struct IsotropicElastic
{
  double youngs;
  double poisson;
  double lame() const { return youngs * poisson / ((1 + poisson) * (1 - 2 * poisson)); }
  double shear() const { return youngs / (2 * (1 + poisson)); }
};

/// lambda^T K_e(X) u for the element with nodes X, displacements u and adjoint lambda (nodeCount
/// of each).
double elementWork(SolidElement element, const Vec3* X, const Vec3* u, const Vec3* lambda, const IsotropicElastic& material);

/// d(lambda^T K_e(X) u)/dX_b added to out[b], b = 0 .. nodeCount - 1.
void addElementWorkDerivative(
  SolidElement element, const Vec3* X, const Vec3* u, const Vec3* lambda, const IsotropicElastic& material, Vec3* out);

/// The element's volume, integrated at the solver's points.
double elementVolume(SolidElement element, const Vec3* X);

/// dV_e/dX_b added to out[b].
void addElementVolumeDerivative(SolidElement element, const Vec3* X, Vec3* out);

/// The solid elements of a mesh in flat arrays: element e, of type type[e] and material
/// material[e], has the nodes nodes[start[e]] .. nodes[start[e + 1] - 1] (indices into the
/// node arrays, VTK's order).
struct SolidMesh
{
  std::vector<SolidElement> type;
  std::vector<long> start{ 0 };
  std::vector<int> nodes;
  std::vector<int> material;
  long elements() const { return static_cast<long>(type.size()); }
  void add(SolidElement element, const int* elementNodes, int elementMaterial);
};

/// sum_e lambda^T K_e u and its gradient sum_e d(lambda^T K_e u)/dX at every node (X, u, lambda:
/// one per node; materials by index). The elements in parallel, each node's sum in element order:
/// the same bits for any thread count. Throws InvalidInputException naming a degenerate element
/// or a node or material index out of range.
double meshWork(const SolidMesh& mesh, const PointList& X, const PointList& u, const PointList& lambda,
  const std::vector<IsotropicElastic>& materials, PointList* gradient);

/// sum_e weight[material e] V_e (weights per material: densities for the mass, 1 for the volume,
/// 0 leaves the material's elements out) and its gradient at every node, as meshWork.
double meshVolume(const SolidMesh& mesh, const PointList& X, const std::vector<double>& weight, PointList* gradient);
} // namespace mlsdeform
