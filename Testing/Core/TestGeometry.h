// Generated test geometry: structured tetrahedral boxes and triangulated planes.
#pragma once

#include "Sampling/Sampling.h"

#include <random>

namespace testgeometry
{
using mlsdeform::PointList;
using mlsdeform::SamplingDomain;
using mlsdeform::Vec3;

/// A box [0,size] split into n^3 cubes of 6 tetrahedra each, with its boundary triangles.
inline SamplingDomain tetrahedralBox(int n, const Vec3& size)
{
  SamplingDomain box;
  auto id = [n](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        box.points.push_back(Vec3(i, j, k).cwiseProduct(size) / n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const int v[8] = { id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
          id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1) };
        const int tets[6][4] = { { 0, 1, 2, 6 }, { 0, 2, 3, 6 }, { 0, 3, 7, 6 }, { 0, 7, 4, 6 }, { 0, 4, 5, 6 }, { 0, 5, 1, 6 } };
        for (const auto& t : tets)
          box.tetrahedra.push_back({ v[t[0]], v[t[1]], v[t[2]], v[t[3]] });
      }
  // boundary faces: two triangles per boundary quad
  auto quad = [&](int a, int b, int c, int d) {
    box.triangles.push_back({ a, b, c });
    box.triangles.push_back({ a, c, d });
  };
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
    {
      quad(id(a, b, 0), id(a + 1, b, 0), id(a + 1, b + 1, 0), id(a, b + 1, 0));
      quad(id(a, b, n), id(a + 1, b, n), id(a + 1, b + 1, n), id(a, b + 1, n));
      quad(id(a, 0, b), id(a + 1, 0, b), id(a + 1, 0, b + 1), id(a, 0, b + 1));
      quad(id(a, n, b), id(a + 1, n, b), id(a + 1, n, b + 1), id(a, n, b + 1));
      quad(id(0, a, b), id(0, a + 1, b), id(0, a + 1, b + 1), id(0, a, b + 1));
      quad(id(n, a, b), id(n, a + 1, b), id(n, a + 1, b + 1), id(n, a, b + 1));
    }
  return box;
}

/// A plane z = 0 of nx x ny quads (two triangles each) over [0,lx] x [0,ly].
inline SamplingDomain triangulatedPlane(int nx, int ny, double lx, double ly)
{
  SamplingDomain plane;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      plane.points.push_back(Vec3(lx * i / nx, ly * j / ny, 0));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
    {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      plane.triangles.push_back({ a, b, c });
      plane.triangles.push_back({ a, c, d });
    }
  return plane;
}

/// The largest distance between corresponding points of two lists.
inline double maxDistance(const PointList& a, const PointList& b)
{
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

inline PointList randomPoints(int count, const Vec3& lower, const Vec3& upper, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  PointList out;
  for (int i = 0; i < count; ++i)
    out.push_back(lower + Vec3(uniform(random), uniform(random), uniform(random)).cwiseProduct(upper - lower));
  return out;
}
}
