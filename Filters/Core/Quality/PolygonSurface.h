// A surface of polygons on some of a mesh's points (a body's boundary patches, the faces that bound
// a set of cells) and the measures of a design's geometric constraints on it, with their exact
// gradients: the volume it encloses by the divergence theorem, V = alpha sum_f (P C_f) . S_f
// (C_f, S_f a face's centre and area vector as FaceQuality measures them; alpha = 1/3, P = I for
// a closed surface; alpha = 1/2, P = I - a a^T for an extruded shape open along the axis a, whose
// in-plane field has no flux through the front and back), and its area A = sum_f |S_f|. The faces
// are measured in parallel, each point's terms summed in the order of its corners: the same bits
// for any thread count.
#pragma once

#include "Common/CoreTypes.h"

#include <vector>

namespace mlsdeform
{
class PolygonSurface
{
public:
  /// Polygons f = 0 .. starts.size() - 2 with the points corners[starts[f]] .. corners[starts[f + 1] - 1]
  /// (indices into the point lists the measures get). The volume is positive when the polygons'
  /// area vectors (by the right-hand rule) point out of it.
  PolygonSurface(const std::vector<long>& starts, const std::vector<int>& corners);

  /// The points the polygons have, ascending: the rows of the measures' gradients.
  const std::vector<int>& points() const { return Points; }
  std::size_t polygons() const { return Starts.size() - 1; }
  /// The largest point index + 1 (0 without polygons): the point lists must hold that many.
  std::size_t pointsNeeded() const { return Points.empty() ? 0 : static_cast<std::size_t>(Points.back()) + 1; }

  /// V = alpha sum_f (P C_f) . S_f on points (P symmetric), and dV/dX at points() into gradient
  /// (one row per point of points()) when it is given.
  double volume(const PointList& points, const Eigen::Matrix3d& P, double alpha, PointList* gradient) const;
  /// A = sum_f |S_f|, and dA/dX as volume's (a face of no area has no direction: no gradient).
  double area(const PointList& points, PointList* gradient) const;

private:
  /// sum_f term(g_f) over the faces' geometries g_f, term(g, centreBar, areaBar) giving a face's
  /// value and (when the gradient is asked) its derivatives along C_f and S_f.
  template <typename Term>
  double sum(const PointList& points, Term term, PointList* gradient) const;

  std::vector<int> Points;            // ascending
  std::vector<long> Starts;
  std::vector<int> Corners;           // indices into Points
  std::vector<long> CornersOfStart{ 0 }; // point i's corners are CornersOf[CornersOfStart[i] ..]
  std::vector<long> CornersOf;        // ascending per point
};
} // namespace mlsdeform
