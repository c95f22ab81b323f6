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

/// v^T f_e for a body force b per unit volume (gravity: the density times the acceleration), f_e
/// integrated at the solver's points: sum_g w_g |det J_g| v(xi_g) . b (v: one vector a node).
double elementBodyWork(SolidElement element, const Vec3* X, const Vec3* v, const Vec3& b);

/// d(v^T f_e)/dX_b added to out[b]: sum_g w_g |det J_g| (v(xi_g) . b) grad N_b (the shape
/// functions' values do not move with the nodes, the volume does).
void addElementBodyWorkDerivative(SolidElement element, const Vec3* X, const Vec3* v, const Vec3& b, Vec3* out);

/// v^T f for a pressure p on a face of the element (X, v: the element's nodes), as ccx loads it:
/// f_a = -p sum_g w_g N_a (dx/dxi x dx/deta), the face's normal out of the element (positive
/// pressure pushes inward), on the undeformed geometry (a linear step: no follower load).
double facePressureWork(const ElementFace& face, const Vec3* X, const Vec3* v, double p);

/// d(v^T f)/dX_b added to out[b] (the element's nodes): -p sum_g w_g (dN_b/dxi (t2 x v) +
/// dN_b/deta (v x t1)), t1 = dx/dxi, t2 = dx/deta, v at the point.
void addFacePressureWorkDerivative(const ElementFace& face, const Vec3* X, const Vec3* v, double p, Vec3* out);

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

/// sum_e v^T f_e for the body force per unit volume force[e] of each element (zero: none) and
/// its gradient at every node, as meshWork.
double meshBodyWork(const SolidMesh& mesh, const PointList& X, const PointList& v, const std::vector<Vec3>& force, PointList* gradient);

/// The von Mises stress sqrt(3/2 s : s) (s the deviator of sigma = l tr(grad u) I + m (grad u +
/// grad u^T)) at each of the element's integration points, in their order.
std::vector<double> elementVonMises(SolidElement element, const Vec3* X, const Vec3* u, const IsotropicElastic& material);

/// For weights c_g of the integration points: sum_g c_g d(sigma_vm,g)/du_a added to dU[a] and
/// sum_g c_g d(sigma_vm,g)/dX_b at fixed u added to dX[b]. With G = grad u at the point,
/// d(sigma_vm)/dG = 3 m s / sigma_vm (s symmetric, tr s = 0), so d/du_a = (3 m / sigma_vm) s grad N_a
/// and, as d(grad N_a)/dX_b = -grad N_b (grad N_a)^T, d/dX_b = -(3 m / sigma_vm) G^T s grad N_b
/// (0 at a point without stress).
void addElementVonMisesDerivatives(
  SolidElement element, const Vec3* X, const Vec3* u, const IsotropicElastic& material, const double* c, Vec3* dU, Vec3* dX);

/// The KS aggregate of the von Mises stresses at the integration points of `elements` (indices
/// into the mesh), in its max-shifted form with a reference stress S > 0 and weight rho > 0:
///   J = m + (S / rho) ln sum_g exp(rho (sigma_g - m) / S),  m = max_g sigma_g,
/// so that m <= J <= m + S ln(N) / rho (N points). dJ/du (at every node) and dJ/dX at fixed u
/// into the gradients when given; the elements in parallel, sums in element order.
double meshStressAggregate(const SolidMesh& mesh, const PointList& X, const PointList& u, const std::vector<IsotropicElastic>& materials,
  const std::vector<long>& elements, double rho, double reference, PointList* dJdu, PointList* dJdX);

/// A pressure on face `face` (ccx's face number) of element `element`.
struct FacePressure
{
  long element;
  int face;
  double pressure;
};

/// sum over the faces of v^T f and its gradient at every node (the faces in their order: the same
/// bits for any thread count). Throws InvalidInputException for a face the element does not have.
double meshPressureWork(const SolidMesh& mesh, const PointList& X, const PointList& v, const std::vector<FacePressure>& faces,
  PointList* gradient);

/// sum_e weight[material e] V_e (weights per material: densities for the mass, 1 for the volume,
/// 0 leaves the material's elements out) and its gradient at every node, as meshWork.
double meshVolume(const SolidMesh& mesh, const PointList& X, const std::vector<double>& weight, PointList* gradient);
} // namespace mlsdeform
