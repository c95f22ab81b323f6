// The scaled Jacobian of isoparametric finite elements, linear and quadratic: the measure of the
// paper's FEM meshes (section 7.3, Figs. 12 and 13), and what tells a solver's element inverted.
//
// At a point of the reference element, J = dx/d(xi) (columns: the derivatives along the
// reference axes) and the scaled Jacobian is det J / (|J1| |J2| |J3|), scaled so that the ideal
// element (regular tetrahedron, cube, right prism on an equilateral triangle) has 1. On simplices
// (the tetrahedron, the wedge's triangle) the axes are the edges from a corner: at a corner node
// its own, at an interior point the least over the corners. The points: every corner node, and
// for a quadratic element also its integration points (C3D10: 4; C3D20: 2x2x2 and 3x3x3, so
// that C3D20R's are among them; C3D15: 3 x 3) and the hexahedron's centre. On linear elements
// this is verdict's scaled Jacobian (tetrahedra and hexahedra: corners and centre), with the sign
// of VTK's node order: verdict's wedge is positive for the mirror image of VTK's wedge.
#pragma once

#include "Common/CoreTypes.h"

#include <vector>

namespace mlsdeform
{
/// The elements measured, each with VTK's node order (vtkQuadraticTetra, vtkQuadraticHexahedron,
/// vtkQuadraticWedge: the corners, then the midside nodes edge by edge).
enum class ElementShape
{
  Tetra4,
  Tetra10,
  Hexa8,
  Hexa20,
  Wedge6,
  Wedge15,
};

struct ElementJacobian
{
  double minScaled;  // the least scaled Jacobian over the points, in [-1, 1]
  bool inverted;     // det J <= 0 at some point: the solver rejects the element
};

/// The element whose nodes are nodes[0 .. n-1] (n of its shape), measured at its points.
ElementJacobian elementJacobian(ElementShape shape, const Vec3* nodes);

/// The scaled Jacobian at each of the element's points, frame by frame (a corner's edges on
/// simplices), appended to out: elementJacobian's least is their minimum.
void scaledJacobians(ElementShape shape, const Vec3* nodes, std::vector<double>& out);

/// Adds sum_j weights[j] d(sj_j)/d(node) to gradient[node] for the values of scaledJacobians
/// (in their order): sj = det J / (|J1| |J2| |J3|) times the shape's scale, J linear in the nodes
/// (none where sj is at -1 or 1, where the clamp holds it).
void addScaledJacobianGradient(ElementShape shape, const Vec3* nodes, const double* weights, Vec3* gradient);
} // namespace mlsdeform
