#include "Basis/ShellOperators.h"

#include "Common/BoundingBox.h"

#include <cmath>

namespace mlsdeform
{
namespace
{
// A triangle's corners, area and unit normal; degenerate when its area is (relatively) zero.
struct Triangle
{
  std::array<Vec3, 3> p;
  double area = 0;
  Vec3 normal = Vec3::Zero();
  bool degenerate = true;
  /// cot of the angle at corner c
  double cot(int c) const
  {
    const Vec3 a = p[(c + 1) % 3] - p[c], b = p[(c + 2) % 3] - p[c];
    return a.dot(b) / a.cross(b).norm();
  }
};

Triangle triangle(const SamplingDomain& mesh, const std::array<int, 3>& t, double length)
{
  Triangle tri;
  for (int c = 0; c < 3; ++c)
  {
    tri.p[c] = mesh.points[t[c]];
  }
  const Vec3 cross = (tri.p[1] - tri.p[0]).cross(tri.p[2] - tri.p[0]);
  tri.area = cross.norm() / 2;
  tri.degenerate = !(tri.area > 1e-14 * length * length);
  if (!tri.degenerate)
  {
    tri.normal = cross.normalized();
  }
  return tri;
}

void checkMesh(const SamplingDomain& mesh)
{
  if (mesh.points.empty() || mesh.triangles.empty())
  {
    throw InvalidInputException("the shell deformation needs a triangle mesh; the input has no triangles");
  }
  requireFinite(mesh.points, "mesh points");
  const int n = static_cast<int>(mesh.points.size());
  for (const auto& t : mesh.triangles)
  {
    for (int v : t)
    {
      if (v < 0 || v >= n)
      {
        throw InvalidInputException("a triangle refers to vertex " + std::to_string(v) + " of " + std::to_string(n));
      }
    }
  }
}
}

std::vector<double> mixedAreas(const SamplingDomain& mesh)
{
  checkMesh(mesh);
  const double length = largestSide(mesh.points);
  std::vector<double> area(mesh.points.size(), 0.0);
  for (const auto& t : mesh.triangles)
  {
    const Triangle tri = triangle(mesh, t, length);
    if (tri.degenerate)
    {
      continue;
    }
    std::array<double, 3> cot;
    bool obtuse = false;
    for (int c = 0; c < 3; ++c)
    {
      cot[c] = tri.cot(c);
      obtuse = obtuse || cot[c] < 0;
    }
    for (int c = 0; c < 3; ++c)
    {
      if (!obtuse)
      {
        // Voronoi region of corner P = c: 1/8 (|PR|^2 cot Q + |PQ|^2 cot R) (Meyer et al., sec. 3.3)
        const int q = (c + 1) % 3, r = (c + 2) % 3;
        area[t[c]] += ((tri.p[r] - tri.p[c]).squaredNorm() * cot[q] + (tri.p[q] - tri.p[c]).squaredNorm() * cot[r]) / 8;
      }
      else
      {
        area[t[c]] += cot[c] < 0 ? tri.area / 2 : tri.area / 4;
      }
    }
  }
  return area;
}

DeformationEnergy shellEnergy(const SamplingDomain& mesh)
{
  const std::vector<double> vertexArea = mixedAreas(mesh);
  const long n = static_cast<long>(mesh.points.size());
  for (long i = 0; i < n; ++i)
  {
    if (!(vertexArea[i] > 0))
    {
      throw InvalidInputException("vertex " + std::to_string(i) + " lies in no triangle of positive area: the shell deformation moves triangle surfaces only (remove unused points with Clean first)");
    }
  }
  const double length = largestSide(mesh.points);
  const double T = static_cast<double>(mesh.triangles.size());
  std::vector<Eigen::Triplet<double>> gradient, laplacian;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
  {
    const auto& t = mesh.triangles[k];
    const Triangle tri = triangle(mesh, t, length);
    if (tri.degenerate)
    {
      continue;
    }
    // grad psi_c = N x (p_{c+2} - p_{c+1}) / (2 A_t), rows weighted by sqrt(A_t / T) (eq. 6)
    const double rowScale = std::sqrt(tri.area / T);
    for (int c = 0; c < 3; ++c)
    {
      const Vec3 g = tri.normal.cross(tri.p[(c + 2) % 3] - tri.p[(c + 1) % 3]) / (2 * tri.area);
      for (int d = 0; d < 3; ++d)
      {
        gradient.emplace_back(3 * static_cast<long>(k) + d, t[c], rowScale * g[d]);
      }
    }
    // cot of the angle at c weighs the opposite edge (a, b) in both a's and b's Laplacian (eq. 7)
    for (int c = 0; c < 3; ++c)
    {
      const double w = tri.cot(c);
      const int a = t[(c + 1) % 3], b = t[(c + 2) % 3];
      for (const auto& [i, j] : { std::pair<int, int>(a, b), std::pair<int, int>(b, a) })
      {
        // row i of L: sqrt(A_i l^2 / n) / (2 A_i) sum_j w_ij (d_j - d_i)
        const double scale = length * std::sqrt(vertexArea[i] / n) / (2 * vertexArea[i]);
        laplacian.emplace_back(i, j, scale * w);
        laplacian.emplace_back(i, i, -scale * w);
      }
    }
  }
  DeformationEnergy energy;
  energy.stretch.resize(3 * static_cast<long>(mesh.triangles.size()), n);
  energy.stretch.setFromTriplets(gradient.begin(), gradient.end());
  energy.bend.resize(n, n);
  energy.bend.setFromTriplets(laplacian.begin(), laplacian.end());
  return energy;
}

PiecewiseLinearBasis::PiecewiseLinearBasis(const PointList& vertices)
  : Vertices(vertices)
  , Tree(vertices)
  , Tolerance(1e-9 * largestSide(vertices))
{
}

void PiecewiseLinearBasis::evaluate(const Vec3& x, ShapeFunctionValues& out, bool withDerivatives) const
{
  if (withDerivatives)
  {
    throw std::logic_error("piecewise linear shape functions have no pointwise derivatives; use shellEnergy");
  }
  out.index.clear();
  out.value.clear();
  const int j = Tree.nearest(x);
  if (j >= 0 && (Vertices[j] - x).norm() <= Tolerance)
  {
    out.index.push_back(j);
    out.value.push_back(1.0);
  }
}
namespace
{
// The ridge of the vertex-based energies (DeformationEnergy::ridge).
constexpr double SurfaceVertexRidge = 1e-9;
}

DeformationEnergy surfaceVertexEnergy(const ShapeFunctions& basis, const SamplingDomain& mesh)
{
  const DeformationEnergy shell = shellEnergy(mesh);
  std::vector<int> outside;
  const SparseRowMatrix Phi = subspaceMatrix(basis, mesh.points, &outside);
  if (!outside.empty())
  {
    throw InvalidInputException("vertex " + std::to_string(outside.front()) + " (and " +
      std::to_string(outside.size() - 1) + " more) lies outside every support of the basis");
  }
  // about as many shape functions as vertices: some combinations move no vertex
  return { SparseRowMatrix(shell.stretch * Phi), SparseRowMatrix(shell.bend * Phi), SurfaceVertexRidge };
}
} // namespace mlsdeform
