#include "Quality/FaceQuality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iterator>
#include <numeric>
#include <omp.h>
#include <stdexcept>
#include <string>

namespace mlsdeform
{
namespace
{
// OpenFOAM's ROOTVSMALL: keeps divisions finite for degenerate faces.
constexpr double RootVerySmall = 1e-150;
}

FaceGeometry faceGeometry(const PointList& points, const int* face, std::size_t n)
{
  FaceGeometry g;
  if (n < 3)
  {
    return g;
  }
  if (n == 3) // a triangle directly, as OpenFOAM does (makeFaceCentresAndAreas)
  {
    const Vec3& p0 = points[face[0]];
    const Vec3& p1 = points[face[1]];
    const Vec3& p2 = points[face[2]];
    g.centre = (p0 + p1 + p2) / 3;
    g.area = (p1 - p0).cross(p2 - p0) / 2;
    return g;
  }
  Vec3 average = Vec3::Zero(); // OpenFOAM's estimate: the sum of the points over their number
  for (std::size_t i = 0; i < n; ++i)
  {
    average += points[face[i]];
  }
  average /= static_cast<double>(n);
  // triangles (p_i, p_i+1, average): centre (p_i + p_i+1 + average) / 3 weighted by area
  Vec3 sumN = Vec3::Zero(), sumAc = Vec3::Zero();
  double sumA = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3& p = points[face[i]];
    const Vec3& q = points[face[i + 1 < n ? i + 1 : 0]];
    const Vec3 normal = (q - p).cross(average - p);
    const double a = normal.norm();
    sumN += normal;
    sumA += a;
    sumAc += a * (p + q + average);
  }
  g.centre = sumA > RootVerySmall ? Vec3(sumAc / (3 * sumA)) : average;
  g.area = sumN / 2;
  return g;
}

CellGeometry cellGeometry(const PointList& points, const std::vector<std::vector<int>>& faces)
{
  std::vector<FaceGeometry> g;
  g.reserve(faces.size());
  for (const auto& f : faces)
  {
    g.push_back(faceGeometry(points, f));
  }
  return cellGeometry(g);
}

CellGeometry cellGeometry(const std::vector<FaceGeometry>& faces)
{
  CellGeometry c;
  Vec3 estimate = Vec3::Zero(); // OpenFOAM's: the sum of the face centres over their number
  for (const FaceGeometry& face : faces)
  {
    estimate += face.centre;
  }
  estimate /= static_cast<double>(std::max<std::size_t>(1, faces.size()));
  // pyramids on the faces with apex at the estimate: volume |S . (C_f - apex)| / 3, centroid
  // 3/4 C_f + 1/4 apex
  double sum = 0;
  for (const FaceGeometry& face : faces)
  {
    const double pyramid3 = std::abs(face.area.dot(face.centre - estimate));
    c.centre += pyramid3 * (0.75 * face.centre + 0.25 * estimate);
    sum += pyramid3;
  }
  c.centre = sum > RootVerySmall ? Vec3(c.centre / sum) : estimate;
  c.volume = sum / 3;
  return c;
}

bool hasNegativePyramid(const std::vector<FaceGeometry>& faces, const Vec3& centre)
{
  return std::any_of(faces.begin(), faces.end(), [&](const FaceGeometry& face) { return face.area.dot(face.centre - centre) < 0; });
}

namespace
{
// The cosine of the angle between d and a face's area vector.
double cosineOf(const Vec3& d, const Vec3& area)
{
  return std::clamp(area.dot(d) / (area.norm() * d.norm() + RootVerySmall), -1.0, 1.0);
}
}

double faceCosine(const Vec3& ownerCentre, const Vec3& neighbourCentre, const Vec3& area)
{
  return cosineOf(neighbourCentre - ownerCentre, area);
}

double nonOrthogonalityOf(double cosine)
{
  return std::acos(cosine) * 180.0 / M_PI;
}

SkewFrame interiorFrame(const Vec3& ownerCentre, const Vec3& neighbourCentre, const FaceGeometry& face)
{
  return { face.centre - ownerCentre, neighbourCentre - ownerCentre, 0.2 };
}

SkewFrame boundaryFrame(const Vec3& ownerCentre, const FaceGeometry& face)
{
  // OpenFOAM's normalised(): zero for a vector of length at most ROOTVSMALL
  const double length = face.area.norm();
  const Vec3 n = length > RootVerySmall ? Vec3(face.area / length) : Vec3::Zero();
  const Vec3 Cpf = face.centre - ownerCentre;
  return { Cpf, n * n.dot(Cpf), 0.4 };
}

namespace
{
// Skewness's offset sv of the face centre and its least extent fd = share |d|: |sv| / fd bounds
// the skewness from above without the face's points.
struct SkewOffset
{
  Vec3 sv;
  double leastExtent;
  double bound() const { return sv.norm() / leastExtent; }
};

SkewOffset skewOffset(const SkewFrame& f, const FaceGeometry& face)
{
  return { f.Cpf - (face.area.dot(f.Cpf) / (face.area.dot(f.d) + RootVerySmall)) * f.d, f.extentShare * f.d.norm() + RootVerySmall };
}

double skewnessOf(const SkewOffset& o, const FaceGeometry& face, const PointList& points, const int* faceIndices, std::size_t n)
{
  const Vec3 svHat = o.sv / (o.sv.norm() + RootVerySmall);
  double fd = o.leastExtent;
  for (std::size_t i = 0; i < n; ++i)
  {
    fd = std::max(fd, std::abs(svHat.dot(points[faceIndices[i]] - face.centre)));
  }
  return o.sv.norm() / fd;
}
}

double skewness(const Vec3& ownerCentre, const Vec3& neighbourCentre, const FaceGeometry& face, const PointList& points,
  const int* faceIndices, std::size_t n)
{
  return skewnessOf(skewOffset(interiorFrame(ownerCentre, neighbourCentre, face), face), face, points, faceIndices, n);
}

double boundarySkewness(const Vec3& ownerCentre, const FaceGeometry& face, const PointList& points, const int* faceIndices, std::size_t n)
{
  return skewnessOf(skewOffset(boundaryFrame(ownerCentre, face), face), face, points, faceIndices, n);
}

CellFaceList::CellFaceList(const std::vector<CellFaces>& cells)
  : CellFaceList(build(static_cast<int>(cells.size()), [&]() {
    return [&](int c, auto add) {
      for (const std::vector<int>& face : cells[c])
      {
        add(face.data(), face.size());
      }
    };
  }))
{
}

InteriorFaces interiorFaces(const CellFaceList& cells)
{
  // Faces grouped by their smallest point (a group holds a few faces; a map keyed by the sorted
  // faces took 6 s on a 1M-cell mesh), in face order, so that the first of a pair is the owner
  // (the lower cell). Groups are matched in parallel: each writes only its own faces' entries.
  const long faceCount = cells.faces();
  UninitializedVector<int> cellOf(static_cast<std::size_t>(faceCount)); // the arrays here: set in parallel loops
#pragma omp parallel for schedule(static)
  for (int c = 0; c < cells.cells(); ++c)
  {
    std::fill(cellOf.begin() + cells.firstFace(c), cellOf.begin() + cells.firstFace(c + 1), c);
  }
  UninitializedVector<int> smallest(static_cast<std::size_t>(faceCount)); // -1: an empty face
  int points = 0;
#pragma omp parallel for reduction(max : points)
  for (long f = 0; f < faceCount; ++f)
  {
    const int* face = cells.face(f);
    const std::size_t n = cells.faceSize(f);
    smallest[f] = -1;
    if (n > 0)
    {
      smallest[f] = *std::min_element(face, face + n);
      points = std::max(points, *std::max_element(face, face + n) + 1);
    }
  }
  // A counting sort by the smallest point, in face order within each group: the faces cut into
  // a few consecutive parts, each counted and then placed by one thread after the parts before it
  // (faster than atomic counters shared by the threads and a sort of every group; the parts'
  // counters cost 8 bytes a point each, hence at most four).
  const int parts = std::max(1, std::min(4, omp_get_max_threads()));
  std::vector<UninitializedVector<long>> next(static_cast<std::size_t>(parts)); // per part and point
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int part = 0; part < parts; ++part)
  {
    next[part].assign(static_cast<std::size_t>(points), 0);
    for (long f = faceCount * part / parts; f < faceCount * (part + 1) / parts; ++f)
    {
      if (smallest[f] >= 0)
      {
        ++next[part][smallest[f]];
      }
    }
  }
  std::vector<long> start(static_cast<std::size_t>(points) + 1, 0); // of each point's group
  for (int p = 0; p < points; ++p)
  {
    long at = start[p];
    for (int part = 0; part < parts; ++part)
    {
      const long count = next[part][p];
      next[part][p] = at; // where the part's first face of the group goes
      at += count;
    }
    start[p + 1] = at;
  }
  UninitializedVector<long> grouped(static_cast<std::size_t>(start.back()));
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int part = 0; part < parts; ++part)
  {
    for (long f = faceCount * part / parts; f < faceCount * (part + 1) / parts; ++f)
    {
      if (smallest[f] >= 0)
      {
        grouped[next[part][smallest[f]]++] = f;
      }
    }
  }
  std::vector<UninitializedVector<long>>().swap(next);
  UninitializedVector<int>().swap(smallest);

  // neighbour[f]: the other cell of the owner's copy f, partner[f] that cell's copy; -2 marks a
  // neighbour's copy
  UninitializedVector<int> neighbour(static_cast<std::size_t>(faceCount));
  UninitializedVector<long> partner(static_cast<std::size_t>(faceCount));
#pragma omp parallel for schedule(static)
  for (long f = 0; f < faceCount; ++f)
  {
    neighbour[f] = -1;
  }
  long shared = faceCount; // the lowest owner's face found in a third cell (the same for any thread count)
#pragma omp parallel
  {
    std::vector<std::pair<long, int>> signature; // per face of the group: the sum and the largest of its points
#pragma omp for schedule(dynamic, 4096) reduction(min : shared)
    for (int p = 0; p < points; ++p)
    {
      const long* begin = grouped.data() + start[p];
      const long count = start[p + 1] - start[p];
      signature.resize(count);
      for (long g = 0; g < count; ++g)
      {
        const int* face = cells.face(begin[g]);
        const std::size_t n = cells.faceSize(begin[g]);
        signature[g] = { std::accumulate(face, face + n, 0L), *std::max_element(face, face + n) };
      }
      // the same points, each as often (a degenerate cell's face may repeat one): first the
      // cheap size and signature, which tell most other faces apart
      auto same = [&](long a, long b) {
        const int* fa = cells.face(begin[a]);
        const int* fb = cells.face(begin[b]);
        const std::size_t n = cells.faceSize(begin[a]);
        return n == cells.faceSize(begin[b]) && signature[a] == signature[b] &&
          std::all_of(fa, fa + n, [&](int point) { return std::count(fa, fa + n, point) == std::count(fb, fb + n, point); });
      };
      for (long a = 0; a < count; ++a)
      {
        const long fa = begin[a];
        for (long b = a + 1; b < count && neighbour[fa] != -2; ++b)
        {
          const long fb = begin[b];
          if (neighbour[fb] == -2 || !same(a, b))
          {
            continue;
          }
          if (neighbour[fa] >= 0)
          {
            shared = std::min(shared, fa);
            break;
          }
          neighbour[fa] = cellOf[fb];
          partner[fa] = fb;
          neighbour[fb] = -2;
        }
      }
    }
  }
  if (shared < faceCount)
  {
    throw std::invalid_argument("a face is shared by more than two cells (cells " + std::to_string(cellOf[shared]) + ", " +
      std::to_string(neighbour[shared]) + " and another)");
  }
  // the owner's copies in face order: counted per chunk of faces, then written in parallel
  constexpr long Chunk = 1 << 16;
  const long chunks = (faceCount + Chunk - 1) / Chunk;
  std::vector<long> offset(static_cast<std::size_t>(chunks) + 1, 0);
#pragma omp parallel for schedule(static)
  for (long c = 0; c < chunks; ++c)
  {
    offset[c + 1] = std::count_if(neighbour.begin() + c * Chunk, neighbour.begin() + std::min(faceCount, (c + 1) * Chunk),
      [](int n) { return n >= 0; });
  }
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  InteriorFaces faces(static_cast<std::size_t>(offset.back()));
#pragma omp parallel for schedule(static)
  for (long c = 0; c < chunks; ++c)
  {
    long next = offset[c];
    for (long f = c * Chunk; f < std::min(faceCount, (c + 1) * Chunk); ++f)
    {
      if (neighbour[f] >= 0)
      {
        faces[next++] = InteriorFace{ cellOf[f], neighbour[f], f, partner[f] };
      }
    }
  }
  return faces;
}

namespace
{
// Whether face b lists the points of face a in reverse (from any point on), so that its geometry
// is a's with the area negated: the neighbour's copy of a sound mesh. A copy listed the other way
// (a cell whose face points inward, which the pyramids then show) or with a point repeated is
// computed from its own list.
bool reversedCopy(const CellFaceList& cells, long a, long b)
{
  const std::size_t n = cells.faceSize(a);
  const int* p = cells.face(a);
  const int* q = cells.face(b);
  if (n < 3 || cells.faceSize(b) != n)
  {
    return false;
  }
  for (std::size_t x = 0; x < n; ++x)
  {
    if (std::find(p + x + 1, p + n, p[x]) != p + n)
    {
      return false; // a point repeated
    }
  }
  const std::size_t j = static_cast<std::size_t>(std::find(q, q + n, p[0]) - q);
  if (j == n)
  {
    return false;
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    if (q[(j + n - k) % n] != p[k])
    {
      return false;
    }
  }
  return true;
}

// Faces this far ahead have their points fetched while a face is computed: the points of a
// large mesh are a cache miss each, and the faces' geometry waited on them.
constexpr long Ahead = 16;
void prefetchPoints(const PointList& points, const int* face, std::size_t n)
{
  for (std::size_t k = 0; k < n; ++k)
  {
    __builtin_prefetch(points[face[k]].data());
  }
}

// Every interior face's geometry (work.faces, out of its owner as listed), then every cell's
// centre (work.centres) and whether it is inverted (hasNegativePyramid): a cell takes an interior
// face's geometry from work.faces (negated for the neighbour's reversed copy) and computes only
// the others', and with its centre its boundary faces' skewness (work.boundarySkewness) while
// their points are at hand (measured after, they were read again: a fifth of a verdict's time).
void cellCentres(const PointList& points, const MeshFaces& mesh, std::vector<unsigned char>& inverted, FaceWorkspace& work)
{
  const CellFaceList& cells = mesh.cells;
  const InteriorFaces& faces = mesh.interior;
  const long interior = static_cast<long>(faces.size());
  const long boundary = static_cast<long>(mesh.boundary.size());
  if (static_cast<long>(work.interiorOf.size()) != cells.faces() || work.boundaryFaces != boundary)
  {
    work.interiorOf.resize(static_cast<std::size_t>(cells.faces()));
#pragma omp parallel for schedule(static)
    for (long f = 0; f < cells.faces(); ++f)
    {
      work.interiorOf[f] = -1;
    }
#pragma omp parallel for schedule(static)
    for (long i = 0; i < interior; ++i)
    {
      work.interiorOf[faces[i].face] = static_cast<int>(i);
      if (reversedCopy(cells, faces[i].face, faces[i].neighbourFace))
      {
        work.interiorOf[faces[i].neighbourFace] = static_cast<int>(-2 - i);
      }
    }
#pragma omp parallel for schedule(static)
    for (long b = 0; b < boundary; ++b)
    {
      work.interiorOf[mesh.boundary[b].face] = static_cast<int>(interior + b);
    }
    work.boundaryFaces = boundary;
  }
  work.boundarySkewness.resize(static_cast<std::size_t>(boundary));
  work.faces.resize(static_cast<std::size_t>(interior));
  // the loops of every verdict in chunks taken as threads come free: a virtual CPU at times runs
  // at half speed, and an even split waits for it (each entry's value is the same either way)
#pragma omp parallel for schedule(dynamic, 4096)
  for (long i = 0; i < interior; ++i)
  {
    if (i + Ahead < interior)
    {
      prefetchPoints(points, cells.face(faces[i + Ahead].face), cells.faceSize(faces[i + Ahead].face));
    }
    work.faces[i] = faceGeometry(points, cells.face(faces[i].face), cells.faceSize(faces[i].face));
  }
  work.centres.resize(cells.cells());
  inverted.resize(cells.cells());
#pragma omp parallel
  {
    std::vector<FaceGeometry> g;
#pragma omp for schedule(dynamic, 2048)
    for (int c = 0; c < cells.cells(); ++c)
    {
      if (c + Ahead < cells.cells())
      {
        for (long f = cells.firstFace(c + Ahead); f < cells.firstFace(c + Ahead + 1); ++f)
        {
          const int i = work.interiorOf[f];
          if (i < -1)
          {
            __builtin_prefetch(&work.faces[-2 - i]); // a neighbour's copy: far from the cell's own faces
          }
          else if (i == -1 || i >= interior)
          {
            prefetchPoints(points, cells.face(f), cells.faceSize(f));
          }
        }
      }
      g.clear();
      bool onBoundary = false;
      for (long f = cells.firstFace(c); f < cells.firstFace(c + 1); ++f)
      {
        const int i = work.interiorOf[f];
        onBoundary = onBoundary || i >= interior;
        if (i >= 0 && i < interior)
        {
          g.push_back(work.faces[i]);
        }
        else if (i < -1)
        {
          g.push_back({ work.faces[-2 - i].centre, -work.faces[-2 - i].area });
        }
        else
        {
          g.push_back(faceGeometry(points, cells.face(f), cells.faceSize(f)));
        }
      }
      work.centres[c] = cellGeometry(g).centre;
      inverted[c] = !g.empty() && hasNegativePyramid(g, work.centres[c]);
      for (long f = cells.firstFace(c); onBoundary && f < cells.firstFace(c + 1); ++f)
      {
        const int i = work.interiorOf[f];
        if (i >= interior)
        {
          const FaceGeometry& face = g[static_cast<std::size_t>(f - cells.firstFace(c))];
          work.boundarySkewness[i - interior] =
            skewnessOf(skewOffset(boundaryFrame(work.centres[c], face), face), face, points, cells.face(f), cells.faceSize(f));
        }
      }
    }
  }
}

// The face measures from the faces' geometry and the cells' centres in work (cellCentres on these
// points). Each interior face is oriented by `orientation`, or, without it, as faceOrientation
// decides on these points, written to `decided`; a boundary face's skewness has no orientation.
void measureFaces(const PointList& points, const MeshFaces& mesh, const std::vector<int>* orientation, std::vector<int>* decided,
  const FaceWorkspace& work, FaceMeasures& m)
{
  const CellFaceList& cells = mesh.cells;
  const InteriorFaces& faces = mesh.interior;
  const long interior = static_cast<long>(faces.size());
  const long boundary = static_cast<long>(mesh.boundary.size());
  m.invertedCells = std::count(m.inverted.begin(), m.inverted.end(), 1);
  m.nonOrthogonality.resize(m.perFace ? faces.size() : 0);
  m.skewness.resize(m.perFace ? faces.size() : 0);
  double leastCosine = 1, maxSkewness = 0; // minimum and maximum: the same for any thread count
  // for the largest alone, a face whose bound is no more than this thread's largest so far cannot
  // change it: its points (a cache miss each) are not read (a tenth of a 1M-cell case's
  // verdict); the largest is the same. (In the loop's body: the thread's own largest, not the
  // shared one a lambda outside it would see.)
#pragma omp parallel for schedule(dynamic, 4096) reduction(min : leastCosine) reduction(max : maxSkewness)
  for (long i = 0; i < interior; ++i)
  {
    if (i + Ahead < interior)
    {
      __builtin_prefetch(work.centres[faces[i + Ahead].neighbour].data());
    }
    FaceGeometry g = work.faces[i];
    const Vec3& P = work.centres[faces[i].owner];
    const Vec3& N = work.centres[faces[i].neighbour];
    const int sign = orientation ? (*orientation)[i] : ((*decided)[i] = g.area.dot(g.centre - P) < 0 ? -1 : 1);
    g.area *= sign;
    const double cosine = faceCosine(P, N, g.area);
    const SkewOffset offset = skewOffset(interiorFrame(P, N, g), g);
    const int* face = cells.face(faces[i].face);
    const double skew = m.perFace || offset.bound() > maxSkewness ? skewnessOf(offset, g, points, face, cells.faceSize(faces[i].face)) : 0.0;
    leastCosine = std::min(leastCosine, cosine);
    maxSkewness = std::max(maxSkewness, skew);
    if (m.perFace)
    {
      m.nonOrthogonality[i] = nonOrthogonalityOf(cosine);
      m.skewness[i] = skew;
    }
  }
  // the boundary faces' skewness, measured with their cells' centres
  for (long b = 0; b < boundary; ++b)
  {
    maxSkewness = std::max(maxSkewness, work.boundarySkewness[b]);
  }
  m.boundarySkewness.assign(work.boundarySkewness.begin(), m.perFace ? work.boundarySkewness.end() : work.boundarySkewness.begin());
  m.maxNonOrthogonality = faces.empty() ? 0 : nonOrthogonalityOf(leastCosine);
  m.maxSkewness = maxSkewness;
}
}

FaceTail faceTail(
  const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation, bool skewness, double width, FaceWorkspace& work)
{
  std::vector<unsigned char> inverted;
  cellCentres(points, mesh, inverted, work);
  const CellFaceList& cells = mesh.cells;
  const InteriorFaces& faces = mesh.interior;
  const long interior = static_cast<long>(faces.size());
  const long count = skewness ? interior + static_cast<long>(mesh.boundary.size()) : interior;
  FaceTail tail;
  if (count == 0)
  {
    return tail;
  }
  // interior face i's oriented geometry, what its measure is defined by, and its skewness; a
  // boundary face's skewness is cellCentres'
  auto geometry = [&](long i) {
    FaceGeometry g = work.faces[i];
    g.area *= orientation[i];
    return g;
  };
  auto frame = [&](long i, const FaceGeometry& g) {
    if (i + Ahead < interior)
    {
      __builtin_prefetch(work.centres[faces[i + Ahead].neighbour].data());
    }
    return interiorFrame(work.centres[faces[i].owner], work.centres[faces[i].neighbour], g);
  };
  auto skewnessAt = [&](long i, const SkewOffset& offset, const FaceGeometry& g) {
    return skewnessOf(offset, g, points, cells.face(faces[i].face), cells.faceSize(faces[i].face));
  };
  // the largest: the least cosine, or the skewness where its bound exceeds this thread's largest;
  // each face's cosine (or skewness bound; a boundary face's skewness) kept for the tail's pass
  work.screen.resize(static_cast<std::size_t>(count));
  double leastCosine = 1, largestSkewness = 0;
#pragma omp parallel for schedule(dynamic, 4096) reduction(min : leastCosine) reduction(max : largestSkewness)
  for (long j = 0; j < count; ++j)
  {
    if (j >= interior)
    {
      work.screen[j] = work.boundarySkewness[j - interior];
      largestSkewness = std::max(largestSkewness, work.screen[j]);
      continue;
    }
    const FaceGeometry g = geometry(j);
    const SkewFrame f = frame(j, g);
    if (!skewness)
    {
      work.screen[j] = cosineOf(f.d, g.area);
      leastCosine = std::min(leastCosine, work.screen[j]);
      continue;
    }
    const SkewOffset offset = skewOffset(f, g);
    work.screen[j] = offset.bound();
    if (work.screen[j] > largestSkewness)
    {
      largestSkewness = std::max(largestSkewness, skewnessAt(j, offset, g));
    }
  }
  tail.largest = skewness ? largestSkewness : nonOrthogonalityOf(leastCosine);
  const double floor = tail.largest - width;
  // the non-orthogonality decreases with the cosine: no face of a cosine above cos(floor) is in
  // the tail (the margin keeps a face at the floor that rounding puts just above it)
  const double mostCosine = floor > 0 ? std::cos(floor * M_PI / 180.0) + 1e-12 : 2.0;
  // in fixed blocks, concatenated in block order: the same faces in face order for any thread count
  constexpr long Block = 4096;
  const long blocks = (count + Block - 1) / Block;
  std::vector<std::vector<std::pair<long, double>>> found(static_cast<std::size_t>(blocks));
#pragma omp parallel for schedule(dynamic)
  for (long b = 0; b < blocks; ++b)
  {
    for (long j = b * Block; j < std::min(count, (b + 1) * Block); ++j)
    {
      if (skewness ? work.screen[j] < floor : work.screen[j] > mostCosine)
      {
        continue;
      }
      double q = work.screen[j]; // a boundary face's skewness
      if (j < interior)
      {
        const FaceGeometry g = geometry(j);
        q = skewness ? skewnessAt(j, skewOffset(frame(j, g), g), g) : nonOrthogonalityOf(work.screen[j]);
      }
      if (q >= floor)
      {
        found[b].emplace_back(j, q);
      }
    }
  }
  for (const auto& block : found)
  {
    for (const auto& [face, q] : block)
    {
      tail.faces.push_back(face);
      tail.values.push_back(q);
    }
  }
  return tail;
}

MeshFaces ownerNeighbourFaces(const std::vector<int>& start, const std::vector<int>& points, const std::vector<int>& owner,
  const std::vector<int>& neighbour, int pointCount)
{
  const long faceCount = static_cast<long>(start.size()) - 1;
  const long internal = static_cast<long>(neighbour.size());
  if (faceCount < 0 || static_cast<long>(owner.size()) != faceCount || internal > faceCount || start.front() != 0 ||
    start.back() != static_cast<long>(points.size()) || !std::is_sorted(start.begin(), start.end()))
  {
    throw std::invalid_argument("the faces (" + std::to_string(faceCount) + "), owners (" + std::to_string(owner.size()) +
      ") and neighbours (" + std::to_string(internal) + ") do not fit together");
  }
  if (std::any_of(points.begin(), points.end(), [&](int p) { return p < 0 || p >= pointCount; }))
  {
    throw std::invalid_argument("a face has a point index outside 0 .. " + std::to_string(pointCount - 1));
  }
  int cells = 0;
  for (long f = 0; f < faceCount; ++f)
  {
    const int o = owner[f], n = f < internal ? neighbour[f] : o + 1;
    if (o < 0 || n < 0 || o == n)
    {
      throw std::invalid_argument("face " + std::to_string(f) + " has owner " + std::to_string(o) +
        (f < internal ? " and neighbour " + std::to_string(n) : std::string()));
    }
    cells = std::max({ cells, o + 1, f < internal ? n + 1 : 0 });
  }
  // each cell's faces in face order: a counting sort of the (cell, face) pairs
  std::vector<long> first(static_cast<std::size_t>(cells) + 1, 0);
  for (long f = 0; f < faceCount; ++f)
  {
    ++first[owner[f] + 1];
    if (f < internal)
    {
      ++first[neighbour[f] + 1];
    }
  }
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<long> next(first.begin(), first.end() - 1);
  std::vector<int> faceOf(static_cast<std::size_t>(first.back()));
  std::vector<long> ownerSlot(static_cast<std::size_t>(internal)); // an interior face's place in its owner's list
  std::vector<long> neighbourSlot(static_cast<std::size_t>(internal)); // and in its neighbour's
  for (long f = 0; f < faceCount; ++f)
  {
    if (f < internal)
    {
      ownerSlot[f] = next[owner[f]] - first[owner[f]];
      neighbourSlot[f] = next[neighbour[f]] - first[neighbour[f]];
      faceOf[next[neighbour[f]]++] = static_cast<int>(f);
    }
    faceOf[next[owner[f]]++] = static_cast<int>(f);
  }
  for (int c = 0; c < cells; ++c)
  {
    if (first[c] == first[c + 1])
    {
      throw std::invalid_argument("cell " + std::to_string(c) + " has no face");
    }
  }
  MeshFaces mesh;
  mesh.cells = CellFaceList::build(cells, [&]() {
    return [&, reversed = std::vector<int>()](int c, auto add) mutable {
      for (long slot = first[c]; slot < first[c + 1]; ++slot)
      {
        const int f = faceOf[slot];
        const int* face = points.data() + start[f];
        const std::size_t n = static_cast<std::size_t>(start[f + 1] - start[f]);
        if (owner[f] == c)
        {
          add(face, n);
        }
        else
        {
          reversed.assign(std::make_reverse_iterator(face + n), std::make_reverse_iterator(face));
          add(reversed.data(), n);
        }
      }
    };
  });
  mesh.interior.resize(static_cast<std::size_t>(internal));
#pragma omp parallel for schedule(static)
  for (long f = 0; f < internal; ++f)
  {
    mesh.interior[f] = { owner[f], neighbour[f], mesh.cells.firstFace(owner[f]) + ownerSlot[f],
      mesh.cells.firstFace(neighbour[f]) + neighbourSlot[f] };
  }
  mesh.boundary = boundaryFaces(mesh.cells, mesh.interior);
  return mesh;
}

std::vector<int> faceOrientation(const PointList& points, const MeshFaces& mesh, FaceWorkspace& work, FaceMeasures& out)
{
  cellCentres(points, mesh, out.inverted, work);
  std::vector<int> orientation(mesh.interior.size(), 1);
  measureFaces(points, mesh, nullptr, &orientation, work, out);
  return orientation;
}

std::vector<int> faceOrientation(const PointList& points, const MeshFaces& mesh)
{
  FaceWorkspace work;
  FaceMeasures measures;
  return faceOrientation(points, mesh, work, measures);
}

void faceMeasures(
  const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation, FaceWorkspace& work, FaceMeasures& m)
{
  cellCentres(points, mesh, m.inverted, work);
  measureFaces(points, mesh, &orientation, nullptr, work, m);
}

FaceMeasures faceMeasures(const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation)
{
  FaceWorkspace work;
  FaceMeasures m;
  faceMeasures(points, mesh, orientation, work, m);
  return m;
}

BoundaryFaces boundaryFaces(const CellFaceList& cells, const InteriorFaces& interior)
{
  std::vector<unsigned char> copy(static_cast<std::size_t>(cells.faces()), 0);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < static_cast<long>(interior.size()); ++i)
  {
    copy[interior[i].face] = copy[interior[i].neighbourFace] = 1;
  }
  BoundaryFaces boundary;
  for (int c = 0; c < cells.cells(); ++c)
  {
    for (long f = cells.firstFace(c); f < cells.firstFace(c + 1); ++f)
    {
      if (!copy[f])
      {
        boundary.push_back({ c, f });
      }
    }
  }
  return boundary;
}

std::vector<std::uint64_t> boundaryKeys(const PointList& points, const CellFaceList& cells, const BoundaryFaces& boundary)
{
  std::vector<std::uint64_t> keys(boundary.size());
#pragma omp parallel
  {
    std::vector<std::array<std::uint64_t, 3>> corners;
#pragma omp for schedule(static)
    for (long b = 0; b < static_cast<long>(boundary.size()); ++b)
    {
      const int* face = cells.face(boundary[b].face);
      corners.resize(cells.faceSize(boundary[b].face));
      for (std::size_t k = 0; k < corners.size(); ++k)
      {
        for (int c = 0; c < 3; ++c)
        {
          const double x = points[face[k]][c] == 0 ? 0.0 : points[face[k]][c]; // -0 as 0
          std::memcpy(&corners[k][c], &x, sizeof x);
        }
      }
      std::sort(corners.begin(), corners.end());
      std::uint64_t key = corners.size();
      for (const auto& corner : corners)
      {
        for (std::uint64_t bits : corner)
        {
          // splitmix64's finalizer over the key and the next word
          std::uint64_t z = (key ^ bits) + 0x9e3779b97f4a7c15ULL;
          z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
          z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
          key = z ^ (z >> 31);
        }
      }
      keys[b] = key;
    }
  }
  return keys;
}

std::vector<std::uint64_t> repeatedKeys(std::vector<std::uint64_t> keys)
{
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint64_t> repeated;
  for (std::size_t k = 1; k < keys.size(); ++k)
  {
    if (keys[k] == keys[k - 1] && (repeated.empty() || repeated.back() != keys[k]))
    {
      repeated.push_back(keys[k]);
    }
  }
  return repeated;
}

long leaveOutFaces(BoundaryFaces& boundary, const std::vector<std::uint64_t>& keys, const std::vector<std::uint64_t>& between)
{
  if (between.empty())
  {
    return 0;
  }
  std::size_t kept = 0;
  for (std::size_t b = 0; b < boundary.size(); ++b)
  {
    if (!std::binary_search(between.begin(), between.end(), keys[b]))
    {
      boundary[kept++] = boundary[b];
    }
  }
  const long left = static_cast<long>(boundary.size() - kept);
  boundary.resize(kept);
  return left;
}

MeshFaces meshFaces(CellFaceList cells)
{
  MeshFaces mesh;
  mesh.cells = std::move(cells);
  mesh.interior = interiorFaces(mesh.cells);
  mesh.boundary = boundaryFaces(mesh.cells, mesh.interior);
  return mesh;
}

CellGeometry cellGeometry(const PointList& points, const CellFaceList& cells, int cell)
{
  std::vector<FaceGeometry> g;
  for (long f = cells.firstFace(cell); f < cells.firstFace(cell + 1); ++f)
  {
    g.push_back(faceGeometry(points, cells.face(f), cells.faceSize(f)));
  }
  return cellGeometry(g);
}
} // namespace mlsdeform
