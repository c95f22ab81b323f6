// CalculiX's (and Abaqus') isoparametric solid elements as the solver integrates them: the shape
// functions N_a(xi) with their derivatives dN_a/dxi in the reference element, and the integration
// points with their weights, so that a sum over them is the solver's own discrete integral.
//
// Reference elements: tetrahedra 0 <= xi, eta, zeta, xi + eta + zeta <= 1 (volume 1/6; node 0 at
// the origin, 1, 2, 3 on the axes); hexahedra [-1, 1]^3 (volume 8); wedges the triangle
// 0 <= xi, eta, xi + eta <= 1 times zeta in [-1, 1] (volume 1; nodes 0 1 2 at zeta = -1). The
// nodes are in VTK's order (the Mesh File reader's, which for these elements is the deck's:
// corners, then the midside nodes edge by edge).
#pragma once

#include "Common/CoreTypes.h"

#include <string>
#include <vector>

namespace mlsdeform
{
/// The elements, named as in a CalculiX or Abaqus deck.
enum class SolidElement
{
  C3D4,   // linear tetrahedron, 1 point
  C3D10,  // quadratic tetrahedron, 4 points
  C3D8,   // trilinear hexahedron, 2 x 2 x 2 points
  C3D20,  // serendipity hexahedron, 3 x 3 x 3 points
  C3D20R, // the same, reduced: 2 x 2 x 2 points
  C3D6,   // linear wedge, 2 points
  C3D15,  // quadratic wedge, 9 points
};

/// The element of a deck's TYPE= name (C3D10, ...); false for any other.
bool solidElementOf(const std::string& name, SolidElement& element);
std::string nameOf(SolidElement element);

/// The element's number of nodes.
int nodeCount(SolidElement element);

/// A point of the reference element and its weight.
struct IntegrationPoint
{
  Vec3 xi;
  double weight;
};
/// The solver's integration points of the element's stiffness and body loads.
const std::vector<IntegrationPoint>& integrationPoints(SolidElement element);

/// N_a(xi) into N[a] and dN_a/dxi into dN[a], a = 0 .. nodeCount - 1.
void shapeFunctions(SolidElement element, const Vec3& xi, double* N, Vec3* dN);

/// A face of an element as ccx loads it (*DLOAD Pn; e_c3d.f's ifaceq, ifacet, ifacew): its nodes,
/// indices into the element's nodes in VTK's order, listed so that dx/dxi x dx/deta points out of
/// the element; its shape (3, 6, 4 or 8 nodes: triangles on 0 <= xi, eta, xi + eta <= 1, corners
/// first and the midside node of corners k, k + 1 after; quadrilaterals on [-1, 1]^2, corners
/// (-1, -1), (1, -1), (1, 1), (-1, 1)) and the solver's integration points on it (xi, eta, weight).
struct ElementFace
{
  std::vector<int> nodes;
  std::vector<IntegrationPoint> points; // xi[2] unused
};

/// Face `face` (1 .. 6 for hexahedra, 4 for tetrahedra, 5 for wedges) of the element; false for a
/// face it does not have.
bool elementFace(SolidElement element, int face, ElementFace& out);

/// The face's N_a(xi, eta) and their derivatives along xi (dN[a][0]) and eta (dN[a][1]).
void faceShapeFunctions(std::size_t nodes, const Vec3& xi, double* N, Vec3* dN);
} // namespace mlsdeform
