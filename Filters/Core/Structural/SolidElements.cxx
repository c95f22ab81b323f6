#include "Structural/SolidElements.h"

#include <array>
#include <cmath>

namespace mlsdeform
{
namespace
{
constexpr int TetEdges[6][2] = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } }; // nodes 4..9
constexpr int HexCorners[8][3] = { { -1, -1, -1 }, { 1, -1, -1 }, { 1, 1, -1 }, { -1, 1, -1 }, { -1, -1, 1 },
  { 1, -1, 1 }, { 1, 1, 1 }, { -1, 1, 1 } };
constexpr int HexEdges[12][2] = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 4 },
  { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } }; // nodes 8..19
constexpr int WedgeEdges[9][2] = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 }, { 0, 3 }, { 1, 4 },
  { 2, 5 } }; // nodes 6..14

// Tetrahedra: barycentric l = (1 - xi - eta - zeta, xi, eta, zeta), dl_k/dxi the rows below.
// Linear N_k = l_k; quadratic N_k = l_k (2 l_k - 1), edge N_ij = 4 l_i l_j.
void tetrahedron(const Vec3& xi, bool quadratic, double* N, Vec3* dN)
{
  const std::array<double, 4> l = { 1 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2] };
  const std::array<Vec3, 4> dl = { Vec3(-1, -1, -1), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1) };
  for (int k = 0; k < 4; ++k)
  {
    N[k] = quadratic ? l[k] * (2 * l[k] - 1) : l[k];
    dN[k] = quadratic ? Vec3((4 * l[k] - 1) * dl[k]) : dl[k];
  }
  for (int e = 0; quadratic && e < 6; ++e)
  {
    const int i = TetEdges[e][0], j = TetEdges[e][1];
    N[4 + e] = 4 * l[i] * l[j];
    dN[4 + e] = 4 * (l[j] * dl[i] + l[i] * dl[j]);
  }
}

// Hexahedra: the node at natural coordinates a (a midside node's: its edge's mean, 0 along it).
// Trilinear N = prod (1 + a_d xi_d) / 2; serendipity corner N = prod (1 + a_d xi_d) / 2 *
// (sum a_d xi_d - 2), midside (1 - xi_m^2) prod_{d != m} (1 + a_d xi_d) / 2.
void hexahedron(const Vec3& xi, bool quadratic, double* N, Vec3* dN)
{
  static const std::array<std::array<int, 3>, 20> natural = [] {
    std::array<std::array<int, 3>, 20> out;
    for (int n = 0; n < 20; ++n)
    {
      for (int d = 0; d < 3; ++d)
      {
        out[n][d] = n < 8 ? HexCorners[n][d] : (HexCorners[HexEdges[n - 8][0]][d] + HexCorners[HexEdges[n - 8][1]][d]) / 2;
      }
    }
    return out;
  }();
  const int count = quadratic ? 20 : 8;
  for (int n = 0; n < count; ++n)
  {
    const std::array<int, 3>& a = natural[n];
    Vec3 f, df; // the product's factors and their derivatives
    for (int d = 0; d < 3; ++d)
    {
      f[d] = a[d] == 0 ? 1 - xi[d] * xi[d] : (1 + a[d] * xi[d]) / 2;
      df[d] = a[d] == 0 ? -2 * xi[d] : a[d] / 2.0;
    }
    const double product = f[0] * f[1] * f[2];
    Vec3 gradient(df[0] * f[1] * f[2], f[0] * df[1] * f[2], f[0] * f[1] * df[2]);
    if (quadratic && n < 8)
    {
      const double s = a[0] * xi[0] + a[1] * xi[1] + a[2] * xi[2] - 2;
      gradient = gradient * s + product * Vec3(a[0], a[1], a[2]);
      N[n] = product * s;
    }
    else
    {
      N[n] = product;
    }
    dN[n] = gradient;
  }
}

// Wedges: the triangle's l = (1 - xi - eta, xi, eta) times zeta, - at the bottom (0 1 2), + at the
// top. Linear N = l_i (1 -+ zeta) / 2. Quadratic: corners l_i (2 l_i - 1)(1 -+ zeta) / 2 -
// l_i (1 - zeta^2) / 2, triangle edges 2 l_i l_j (1 -+ zeta), vertical edges l_i (1 - zeta^2).
void wedge(const Vec3& xi, bool quadratic, double* N, Vec3* dN)
{
  const std::array<double, 3> l = { 1 - xi[0] - xi[1], xi[0], xi[1] };
  const std::array<Vec3, 3> dl = { Vec3(-1, -1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0) };
  const double zeta = xi[2], bubble = 1 - zeta * zeta;
  const Vec3 dzeta(0, 0, 1);
  for (int corner = 0; corner < 6; ++corner)
  {
    const int i = corner % 3;
    const double side = corner < 3 ? -1 : 1;
    const double level = (1 + side * zeta) / 2;
    if (quadratic)
    {
      N[corner] = l[i] * (2 * l[i] - 1) * level - l[i] * bubble / 2;
      dN[corner] = ((4 * l[i] - 1) * level - bubble / 2) * dl[i] + (l[i] * (2 * l[i] - 1) * side / 2 + l[i] * zeta) * dzeta;
    }
    else
    {
      N[corner] = l[i] * level;
      dN[corner] = level * dl[i] + l[i] * side / 2 * dzeta;
    }
  }
  for (int e = 0; quadratic && e < 9; ++e)
  {
    const int i = WedgeEdges[e][0] % 3, j = WedgeEdges[e][1] % 3;
    if (e < 6)
    {
      const double side = e < 3 ? -1 : 1;
      N[6 + e] = 2 * l[i] * l[j] * (1 + side * zeta);
      dN[6 + e] = 2 * (1 + side * zeta) * (l[j] * dl[i] + l[i] * dl[j]) + 2 * l[i] * l[j] * side * dzeta;
    }
    else
    {
      N[6 + e] = l[i] * bubble;
      dN[6 + e] = bubble * dl[i] - 2 * l[i] * zeta * dzeta;
    }
  }
}

// The tensor product of a 1D Gauss rule on [-1, 1] with itself three times.
std::vector<IntegrationPoint> gaussCube(const std::vector<double>& x, const std::vector<double>& w)
{
  std::vector<IntegrationPoint> points;
  for (std::size_t k = 0; k < x.size(); ++k)
    for (std::size_t j = 0; j < x.size(); ++j)
      for (std::size_t i = 0; i < x.size(); ++i)
        points.push_back({ Vec3(x[i], x[j], x[k]), w[i] * w[j] * w[k] });
  return points;
}
} // namespace

bool solidElementOf(const std::string& name, SolidElement& element)
{
  for (SolidElement e : { SolidElement::C3D4, SolidElement::C3D10, SolidElement::C3D8, SolidElement::C3D20, SolidElement::C3D20R,
         SolidElement::C3D6, SolidElement::C3D15 })
  {
    if (nameOf(e) == name)
    {
      element = e;
      return true;
    }
  }
  return false;
}

std::string nameOf(SolidElement element)
{
  switch (element)
  {
    case SolidElement::C3D4: return "C3D4";
    case SolidElement::C3D10: return "C3D10";
    case SolidElement::C3D8: return "C3D8";
    case SolidElement::C3D20: return "C3D20";
    case SolidElement::C3D20R: return "C3D20R";
    case SolidElement::C3D6: return "C3D6";
    case SolidElement::C3D15: return "C3D15";
  }
  return "";
}

int nodeCount(SolidElement element)
{
  switch (element)
  {
    case SolidElement::C3D4: return 4;
    case SolidElement::C3D10: return 10;
    case SolidElement::C3D8: return 8;
    case SolidElement::C3D20:
    case SolidElement::C3D20R: return 20;
    case SolidElement::C3D6: return 6;
    case SolidElement::C3D15: return 15;
  }
  return 0;
}

const std::vector<IntegrationPoint>& integrationPoints(SolidElement element)
{
  // CalculiX's tables (gauss.f: gauss3d4, gauss3d5, gauss3d2, gauss3d3, gauss3d7, gauss3d10,
  // gauss3d8), as e_c3d.f chooses them per element type
  static const double g2 = 1 / std::sqrt(3.0), g3 = std::sqrt(0.6);
  static const std::vector<IntegrationPoint> tet1 = { { Vec3(0.25, 0.25, 0.25), 1 / 6.0 } };
  static const std::vector<IntegrationPoint> tet4 = [] {
    const double a = 0.5854101966249685, b = 0.1381966011250105;
    return std::vector<IntegrationPoint>{ { Vec3(b, b, b), 1 / 24.0 }, { Vec3(a, b, b), 1 / 24.0 }, { Vec3(b, a, b), 1 / 24.0 },
      { Vec3(b, b, a), 1 / 24.0 } };
  }();
  static const std::vector<IntegrationPoint> hex8 = gaussCube({ -g2, g2 }, { 1, 1 });
  static const std::vector<IntegrationPoint> hex27 = gaussCube({ -g3, 0, g3 }, { 5 / 9.0, 8 / 9.0, 5 / 9.0 });
  static const std::vector<IntegrationPoint> wedge2 = { { Vec3(1 / 3.0, 1 / 3.0, -g2), 0.5 }, { Vec3(1 / 3.0, 1 / 3.0, g2), 0.5 } };
  static const std::vector<IntegrationPoint> wedge9 = [] {
    std::vector<IntegrationPoint> points;
    const double triangle[3][2] = { { 1 / 6.0, 1 / 6.0 }, { 2 / 3.0, 1 / 6.0 }, { 1 / 6.0, 2 / 3.0 } };
    const double zeta[3] = { -g3, 0, g3 }, w[3] = { 5 / 9.0, 8 / 9.0, 5 / 9.0 };
    for (int k = 0; k < 3; ++k)
      for (const auto& t : triangle)
        points.push_back({ Vec3(t[0], t[1], zeta[k]), w[k] / 6.0 });
    return points;
  }();
  switch (element)
  {
    case SolidElement::C3D4: return tet1;
    case SolidElement::C3D10: return tet4;
    case SolidElement::C3D8:
    case SolidElement::C3D20R: return hex8;
    case SolidElement::C3D20: return hex27;
    case SolidElement::C3D6: return wedge2;
    case SolidElement::C3D15: return wedge9;
  }
  return tet1;
}

void shapeFunctions(SolidElement element, const Vec3& xi, double* N, Vec3* dN)
{
  switch (element)
  {
    case SolidElement::C3D4: return tetrahedron(xi, false, N, dN);
    case SolidElement::C3D10: return tetrahedron(xi, true, N, dN);
    case SolidElement::C3D8: return hexahedron(xi, false, N, dN);
    case SolidElement::C3D20:
    case SolidElement::C3D20R: return hexahedron(xi, true, N, dN);
    case SolidElement::C3D6: return wedge(xi, false, N, dN);
    case SolidElement::C3D15: return wedge(xi, true, N, dN);
  }
}
namespace
{
// ccx's faces (e_c3d.f: ifaceq, ifacet, ifacew), 1-based in the deck's node order: corners, then
// midside nodes; 0 ends a shorter face
constexpr int HexFaces[6][8] = { { 4, 3, 2, 1, 11, 10, 9, 12 }, { 5, 6, 7, 8, 13, 14, 15, 16 }, { 1, 2, 6, 5, 9, 18, 13, 17 },
  { 2, 3, 7, 6, 10, 19, 14, 18 }, { 3, 4, 8, 7, 11, 20, 15, 19 }, { 4, 1, 5, 8, 12, 17, 16, 20 } };
constexpr int TetFaces[4][6] = { { 1, 3, 2, 7, 6, 5 }, { 1, 2, 4, 5, 9, 8 }, { 2, 3, 4, 6, 10, 9 }, { 1, 4, 3, 8, 10, 7 } };
constexpr int WedgeFaces[5][8] = { { 1, 3, 2, 9, 8, 7, 0, 0 }, { 4, 5, 6, 10, 11, 12, 0, 0 }, { 1, 2, 5, 4, 7, 14, 10, 13 },
  { 2, 3, 6, 5, 8, 15, 11, 14 }, { 4, 6, 3, 1, 12, 15, 9, 13 } };
// the deck's wedge node k is VTK's node WedgeOrder[k] (the Mesh File reader turns the wedge
// over: Abaqus' 1-2-3 runs the other way round); hexahedra and tetrahedra keep the deck's order
constexpr int WedgeOrder[15] = { 0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13 };

// gauss.f's face rules (gauss2d1 .. gauss2d5)
std::vector<IntegrationPoint> faceRule(int nodes, int points)
{
  const double g2 = 1 / std::sqrt(3.0), g3 = std::sqrt(0.6);
  if (nodes == 3 || nodes == 6)
  {
    return points == 1 ? std::vector<IntegrationPoint>{ { Vec3(1 / 3.0, 1 / 3.0, 0), 0.5 } }
                       : std::vector<IntegrationPoint>{ { Vec3(1 / 6.0, 1 / 6.0, 0), 1 / 6.0 }, { Vec3(2 / 3.0, 1 / 6.0, 0), 1 / 6.0 },
                           { Vec3(1 / 6.0, 2 / 3.0, 0), 1 / 6.0 } };
  }
  if (points == 1)
  {
    return { { Vec3(0, 0, 0), 4.0 } };
  }
  const std::vector<double> x = points == 4 ? std::vector<double>{ -g2, g2 } : std::vector<double>{ -g3, 0, g3 };
  const std::vector<double> w = points == 4 ? std::vector<double>{ 1, 1 } : std::vector<double>{ 5 / 9.0, 8 / 9.0, 5 / 9.0 };
  std::vector<IntegrationPoint> rule;
  for (std::size_t j = 0; j < x.size(); ++j)
    for (std::size_t i = 0; i < x.size(); ++i)
      rule.push_back({ Vec3(x[i], x[j], 0), w[i] * w[j] });
  return rule;
}
} // namespace

bool elementFace(SolidElement element, int face, ElementFace& out)
{
  out.nodes.clear();
  const bool quadratic = element == SolidElement::C3D10 || element == SolidElement::C3D20 || element == SolidElement::C3D20R ||
    element == SolidElement::C3D15;
  const int* listed = nullptr;
  const int* order = nullptr;
  switch (element)
  {
    case SolidElement::C3D4:
    case SolidElement::C3D10:
      if (face < 1 || face > 4)
      {
        return false;
      }
      listed = TetFaces[face - 1];
      break;
    case SolidElement::C3D8:
    case SolidElement::C3D20:
    case SolidElement::C3D20R:
      if (face < 1 || face > 6)
      {
        return false;
      }
      listed = HexFaces[face - 1];
      break;
    case SolidElement::C3D6:
    case SolidElement::C3D15:
      if (face < 1 || face > 5)
      {
        return false;
      }
      listed = WedgeFaces[face - 1];
      order = WedgeOrder;
      break;
  }
  const bool triangle = element == SolidElement::C3D4 || element == SolidElement::C3D10 ||
    ((element == SolidElement::C3D6 || element == SolidElement::C3D15) && face <= 2);
  const int corners = triangle ? 3 : 4;
  const int count = quadratic ? 2 * corners : corners;
  for (int k = 0; k < count; ++k)
  {
    const int deckNode = listed[k] - 1;
    out.nodes.push_back(order ? order[deckNode] : deckNode);
  }
  // e_c3d.f's mint2d: C3D6's quadrilaterals 1 point, C3D20's 3 x 3, C3D10's and C3D15's
  // triangles 3, C3D4's and C3D6's triangles 1, the other quadrilaterals 2 x 2
  int points = 4;
  if (triangle)
  {
    points = quadratic ? 3 : 1;
  }
  else if (element == SolidElement::C3D6)
  {
    points = 1;
  }
  else if (element == SolidElement::C3D20)
  {
    points = 9;
  }
  out.points = faceRule(count, points);
  return true;
}

void faceShapeFunctions(std::size_t nodes, const Vec3& xi, double* N, Vec3* dN)
{
  const double x = xi[0], e = xi[1];
  if (nodes == 3 || nodes == 6)
  {
    // shape3tri, shape6tri: l = (1 - xi - eta, xi, eta)
    const double l[3] = { 1 - x - e, x, e };
    const Vec3 dl[3] = { Vec3(-1, -1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0) };
    for (int k = 0; k < 3; ++k)
    {
      N[k] = nodes == 6 ? l[k] * (2 * l[k] - 1) : l[k];
      dN[k] = nodes == 6 ? Vec3((4 * l[k] - 1) * dl[k]) : dl[k];
    }
    for (int k = 0; nodes == 6 && k < 3; ++k)
    {
      const int i = k, j = (k + 1) % 3;
      N[3 + k] = 4 * l[i] * l[j];
      dN[3 + k] = 4 * (l[j] * dl[i] + l[i] * dl[j]);
    }
    return;
  }
  // shape4q, shape8q: corners at (-1, -1), (1, -1), (1, 1), (-1, 1); midside nodes on the edges
  // 1-2 (eta = -1), 2-3 (xi = 1), 3-4 (eta = 1), 4-1 (xi = -1)
  const double cx[4] = { -1, 1, 1, -1 }, ce[4] = { -1, -1, 1, 1 };
  for (int k = 0; k < 4; ++k)
  {
    const double fx = (1 + cx[k] * x) / 2, fe = (1 + ce[k] * e) / 2;
    if (nodes == 4)
    {
      N[k] = fx * fe;
      dN[k] = Vec3(cx[k] / 2 * fe, fx * ce[k] / 2, 0);
    }
    else
    {
      const double s = cx[k] * x + ce[k] * e - 1;
      N[k] = fx * fe * s;
      dN[k] = Vec3(cx[k] / 2 * fe * s + fx * fe * cx[k], fx * ce[k] / 2 * s + fx * fe * ce[k], 0);
    }
  }
  if (nodes == 8)
  {
    N[4] = (1 - x * x) * (1 - e) / 2;
    dN[4] = Vec3(-x * (1 - e), -(1 - x * x) / 2, 0);
    N[5] = (1 + x) * (1 - e * e) / 2;
    dN[5] = Vec3((1 - e * e) / 2, -(1 + x) * e, 0);
    N[6] = (1 - x * x) * (1 + e) / 2;
    dN[6] = Vec3(-x * (1 + e), (1 - x * x) / 2, 0);
    N[7] = (1 - x) * (1 - e * e) / 2;
    dN[7] = Vec3(-(1 - e * e) / 2, -(1 - x) * e, 0);
  }
}
} // namespace mlsdeform
