#include "Quality/FaceQualityAggregate.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mlsdeform
{
namespace
{
constexpr double RootVerySmall = 1e-150; // FaceQuality's (OpenFOAM's ROOTVSMALL)

// A gradient's entries of one face's term: (point, dq/dX) pairs, summed later in face order.
using Terms = std::vector<std::pair<int, Vec3>>;

void addFace(const PointList& points, const int* face, std::size_t n, const Vec3& centreBar, const Vec3& areaBar, Terms& terms)
{
  PointList bar(n, Vec3::Zero());
  faceGeometryAdjoint(points, face, n, centreBar, areaBar, bar.data());
  for (std::size_t k = 0; k < n; ++k)
  {
    terms.emplace_back(face[k], bar[k]);
  }
}

// d(cell centre)/dX contracted with centreBar, through the cell's faces as listed.
void addCell(const PointList& points, const CellFaceList& cells, int cell, const Vec3& centreBar, Terms& terms)
{
  std::vector<FaceGeometry> g;
  for (long f = cells.firstFace(cell); f < cells.firstFace(cell + 1); ++f)
  {
    g.push_back(faceGeometry(points, cells.face(f), cells.faceSize(f)));
  }
  std::vector<Vec3> cBar(g.size(), Vec3::Zero()), sBar(g.size(), Vec3::Zero());
  addCellGeometryAdjoint(g, centreBar, 0.0, cBar, sBar);
  for (std::size_t k = 0; k < g.size(); ++k)
  {
    const long f = cells.firstFace(cell) + static_cast<long>(k);
    addFace(points, cells.face(f), cells.faceSize(f), cBar[k], sBar[k], terms);
  }
}

// The non-orthogonality's derivatives along the owner's and neighbour's centres and the
// oriented area vector, times weight (acos' slope: none at 0 or 180 degrees).
void nonOrthogonalityAdjoint(const Vec3& P, const Vec3& N, const Vec3& S, double weight, Vec3& Pbar, Vec3& Nbar, Vec3& Sbar)
{
  const Vec3 d = N - P;
  const double ls = S.norm(), ld = d.norm();
  const double cosine = S.dot(d) / (ls * ld + RootVerySmall);
  if (!(std::abs(cosine) < 1) || ls == 0 || ld == 0)
  {
    return;
  }
  const double slope = -weight * 180.0 / M_PI / std::sqrt(1 - cosine * cosine); // dq/dcos
  Sbar += slope * (d / (ls * ld) - cosine * S / (ls * ls));
  const Vec3 dBar = slope * (S / (ls * ld) - cosine * d / (ld * ld));
  Nbar += dBar;
  Pbar -= dBar;
}

// The skewness's (FaceQuality's skewnessOf on Cpf = C_f - P and d, its least extent share |d|)
// derivatives, times weight: along Cpf, d, the oriented area vector, the face centre, and the
// face point that sets its extent.
void skewnessAdjoint(const Vec3& Cpf, const Vec3& d, double share, const FaceGeometry& face, const PointList& points, const int* ids,
  std::size_t n, double weight, Vec3& CpfBar, Vec3& dBar, Vec3& Sbar, Vec3& cBar, Terms& terms)
{
  const Vec3& S = face.area;
  const double den = S.dot(d) + RootVerySmall;
  const double t = S.dot(Cpf) / den;
  const Vec3 sv = Cpf - t * d;
  const double length = sv.norm();
  if (length == 0)
  {
    return; // no skewness: a cone's tip, no derivative
  }
  const Vec3 svHat = sv / (length + RootVerySmall);
  double fd = share * d.norm() + RootVerySmall;
  std::size_t k = n; // the point that sets the extent, or n for share |d|
  for (std::size_t i = 0; i < n; ++i)
  {
    const double v = std::abs(svHat.dot(points[ids[i]] - face.centre));
    if (v > fd)
    {
      fd = v;
      k = i;
    }
  }
  // q = |sv| / fd
  Vec3 svBar = weight / fd * svHat;
  const double fdBar = -weight * length / (fd * fd);
  if (k == n)
  {
    dBar += fdBar * share * d / d.norm();
  }
  else
  {
    const Vec3 r = points[ids[k]] - face.centre;
    const double sigma = svHat.dot(r) < 0 ? -1.0 : 1.0;
    const Vec3 svHatBar = fdBar * sigma * r;
    terms.emplace_back(ids[k], fdBar * sigma * svHat);
    cBar -= fdBar * sigma * svHat;
    svBar += (svHatBar - svHat.dot(svHatBar) * svHat) / length;
  }
  // sv = Cpf - t d, t = S . Cpf / (S . d)
  const double tBar = -svBar.dot(d);
  CpfBar += svBar + tBar * S / den;
  dBar += -t * svBar - tBar * t * S / den;
  Sbar += tBar * (Cpf - t * d) / den;
}

// A boundary face's d = n (n . Cpf), n = S / |S| (FaceQuality's boundaryFrame): dBar taken back
// to Cpf and S.
void boundaryFrameAdjoint(const Vec3& Cpf, const Vec3& S, const Vec3& dBar, Vec3& CpfBar, Vec3& Sbar)
{
  const double length = S.norm();
  if (!(length > RootVerySmall))
  {
    return; // d = 0 there (normalised's zero)
  }
  const Vec3 n = S / length;
  const Vec3 nBar = n.dot(Cpf) * dBar + n.dot(dBar) * Cpf;
  CpfBar += n.dot(dBar) * n;
  Sbar += (nBar - n.dot(nBar) * n) / length;
}

// weight times the derivatives of one face's measure (the face `face` as cell `owner` lists it,
// its area times sign; P the owner's centre, N the neighbour's, or none: a boundary face, its
// owner mirrored) at the face's and the owner's points, into terms; those along N returned.
Vec3 faceTerms(const PointList& points, const CellFaceList& cells, int owner, long face, int sign, const Vec3& P, const Vec3* N,
  QualityMeasure measure, double weight, Terms& terms)
{
  FaceGeometry g = faceGeometry(points, cells.face(face), cells.faceSize(face));
  g.area *= sign;
  Vec3 Pbar = Vec3::Zero(), Nbar = Vec3::Zero(), Sbar = Vec3::Zero(), cBar = Vec3::Zero();
  if (measure == QualityMeasure::NonOrthogonality)
  {
    nonOrthogonalityAdjoint(P, *N, g.area, weight, Pbar, Nbar, Sbar);
  }
  else
  {
    const SkewFrame f = N ? interiorFrame(P, *N, g) : boundaryFrame(P, g);
    const Vec3& Cpf = f.Cpf;
    Vec3 CpfBar = Vec3::Zero(), dBar = Vec3::Zero();
    skewnessAdjoint(Cpf, f.d, f.extentShare, g, points, cells.face(face), cells.faceSize(face), weight, CpfBar, dBar, Sbar, cBar, terms);
    if (N)
    {
      Nbar += dBar;
      Pbar -= dBar;
    }
    else
    {
      boundaryFrameAdjoint(Cpf, g.area, dBar, CpfBar, Sbar);
    }
    cBar += CpfBar;
    Pbar -= CpfBar;
  }
  addFace(points, cells.face(face), cells.faceSize(face), cBar, sign * Sbar, terms);
  addCell(points, cells, owner, Pbar, terms);
  return Nbar;
}
}

void AggregatePart::add(const AggregatePart& other, double rho)
{
  if (other.count == 0)
  {
    return;
  }
  if (count == 0)
  {
    *this = other;
    return;
  }
  const double m = std::max(largest, other.largest);
  sum = sum * std::exp(rho * (largest - m)) + other.sum * std::exp(rho * (other.largest - m));
  largest = m;
  count += other.count;
}

double AggregatePart::value(double rho) const
{
  return count > 0 ? largest + std::log(sum) / rho : 0.0;
}

AggregatePart aggregatePart(const std::vector<double>& q, double rho)
{
  AggregatePart part;
  part.count = static_cast<long>(q.size());
  for (double v : q)
  {
    part.largest = std::max(part.largest, v);
  }
  for (double v : q) // in face order: the same sum for any thread count
  {
    part.sum += std::exp(rho * (v - part.largest));
  }
  return part;
}

FaceAggregate aggregateFaces(const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation, QualityMeasure measure,
  double rho, FaceWorkspace& work)
{
  FaceAggregate a;
  const bool skewness = measure == QualityMeasure::Skewness;
  const std::size_t count = mesh.interior.size() + (skewness ? mesh.boundary.size() : 0);
  const double width = (std::log(std::max<double>(1, static_cast<double>(count))) + 46) / rho;
  a.tail = faceTail(points, mesh, orientation, skewness, width, work);
  a.part.count = static_cast<long>(count);
  if (a.part.count > 0)
  {
    a.part.largest = a.tail.largest;
    for (double v : a.tail.values) // in face order: the same sum for any thread count
    {
      a.part.sum += std::exp(rho * (v - a.part.largest));
    }
  }
  return a;
}

void addAggregateGradient(const PointList& points, const MeshFaces& mesh, const std::vector<int>& orientation, const FaceWorkspace& work,
  const FaceTail& tail, QualityMeasure measure, double rho, const AggregatePart& whole, PointList& gradient)
{
  const CellFaceList& cells = mesh.cells;
  const long interior = static_cast<long>(mesh.interior.size());
  std::vector<std::size_t> heavy; // the tail's faces of weight >= LeastAggregateWeight, in face order
  for (std::size_t t = 0; t < tail.faces.size(); ++t)
  {
    if (std::exp(rho * (tail.values[t] - whole.largest)) / whole.sum >= LeastAggregateWeight)
    {
      heavy.push_back(t);
    }
  }
  std::vector<Terms> terms(heavy.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (long h = 0; h < static_cast<long>(heavy.size()); ++h)
  {
    const long j = tail.faces[heavy[h]]; // an interior face, or boundary face j - interior
    const double weight = std::exp(rho * (tail.values[heavy[h]] - whole.largest)) / whole.sum;
    if (j < interior)
    {
      const InteriorFace& f = mesh.interior[j];
      const Vec3& N = work.centres[f.neighbour];
      const Vec3 Nbar = faceTerms(points, cells, f.owner, f.face, orientation[j], work.centres[f.owner], &N, measure, weight, terms[h]);
      addCell(points, cells, f.neighbour, Nbar, terms[h]);
    }
    else
    {
      const BoundaryFace& f = mesh.boundary[j - interior];
      faceTerms(points, cells, f.owner, f.face, 1, work.centres[f.owner], nullptr, measure, weight, terms[h]);
    }
  }
  for (const Terms& t : terms)
  {
    for (const auto& [point, value] : t)
    {
      gradient[point] += value;
    }
  }
}

Vec3 addFaceMeasureGradient(const PointList& points, const CellFaceList& cells, int owner, long face, int sign, const Vec3& P,
  const Vec3& N, QualityMeasure measure, double weight, PointList& gradient)
{
  Terms terms;
  const Vec3 Nbar = faceTerms(points, cells, owner, face, sign, P, &N, measure, weight, terms);
  for (const auto& [point, value] : terms)
  {
    gradient[point] += value;
  }
  return Nbar;
}

void addCellCentreGradient(const PointList& points, const CellFaceList& cells, int cell, const Vec3& centreBar, PointList& gradient)
{
  Terms terms;
  addCell(points, cells, cell, centreBar, terms);
  for (const auto& [point, value] : terms)
  {
    gradient[point] += value;
  }
}

void faceGeometryAdjoint(
  const PointList& points, const int* face, std::size_t n, const Vec3& centreBar, const Vec3& areaBar, Vec3* cornerBar)
{
  if (n < 3)
  {
    return;
  }
  if (n == 3)
  {
    // centre = (p0 + p1 + p2) / 3, area = e x f / 2 (e = p1 - p0, f = p2 - p0)
    const Vec3 e = points[face[1]] - points[face[0]], f = points[face[2]] - points[face[0]];
    const Vec3 eBar = f.cross(areaBar) / 2, fBar = areaBar.cross(e) / 2;
    cornerBar[0] += centreBar / 3 - eBar - fBar;
    cornerBar[1] += centreBar / 3 + eBar;
    cornerBar[2] += centreBar / 3 + fBar;
    return;
  }
  // faceGeometry again, then its steps backwards
  Vec3 average = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i)
  {
    average += points[face[i]];
  }
  average /= static_cast<double>(n);
  Vec3 sumAc = Vec3::Zero();
  double sumA = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3& p = points[face[i]];
    const Vec3& q = points[face[i + 1 < n ? i + 1 : 0]];
    const double a = (q - p).cross(average - p).norm();
    sumA += a;
    sumAc += a * (p + q + average);
  }
  const Vec3 sumNBar = areaBar / 2;
  Vec3 sumAcBar = Vec3::Zero(), averageBar = Vec3::Zero();
  double sumABar = 0;
  if (sumA > RootVerySmall)
  {
    // centre = sumAc / (3 sumA)
    const Vec3 centre = sumAc / (3 * sumA);
    sumAcBar = centreBar / (3 * sumA);
    sumABar = -centreBar.dot(centre) / sumA;
  }
  else
  {
    averageBar += centreBar;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t iq = i + 1 < n ? i + 1 : 0;
    const Vec3& p = points[face[i]];
    const Vec3& q = points[face[iq]];
    const Vec3 e = q - p, f = average - p;
    const Vec3 normal = e.cross(f);
    const double a = normal.norm();
    // sumA += a, sumAc += a (p + q + average), sumN += normal, normal = e x f
    const double aBar = sumABar + sumAcBar.dot(p + q + average);
    cornerBar[i] += a * sumAcBar;
    cornerBar[iq] += a * sumAcBar;
    averageBar += a * sumAcBar;
    const Vec3 normalBar = sumNBar + (a > 0 ? Vec3(aBar * normal / a) : Vec3::Zero());
    const Vec3 eBar = f.cross(normalBar), fBar = normalBar.cross(e);
    cornerBar[iq] += eBar;
    cornerBar[i] -= eBar + fBar;
    averageBar += fBar;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    cornerBar[i] += averageBar / static_cast<double>(n);
  }
}

void addCellGeometryAdjoint(const std::vector<FaceGeometry>& faces, const Vec3& cellCentreBar, double volumeBar,
  std::vector<Vec3>& centreBar, std::vector<Vec3>& areaBar)
{
  if (faces.empty())
  {
    return;
  }
  const double count = static_cast<double>(faces.size());
  Vec3 estimate = Vec3::Zero();
  for (const FaceGeometry& face : faces)
  {
    estimate += face.centre;
  }
  estimate /= count;
  Vec3 centreSum = Vec3::Zero();
  double sum = 0;
  for (const FaceGeometry& face : faces)
  {
    const double pyramid3 = std::abs(face.area.dot(face.centre - estimate));
    centreSum += pyramid3 * (0.75 * face.centre + 0.25 * estimate);
    sum += pyramid3;
  }
  Vec3 estimateBar = Vec3::Zero(), centreSumBar = Vec3::Zero();
  double sumBar = volumeBar / 3;
  if (sum > RootVerySmall)
  {
    // centre = centreSum / sum
    centreSumBar = cellCentreBar / sum;
    sumBar -= cellCentreBar.dot(centreSum / sum) / sum;
  }
  else
  {
    estimateBar += cellCentreBar;
  }
  for (std::size_t f = 0; f < faces.size(); ++f)
  {
    const FaceGeometry& face = faces[f];
    const double signedPyramid3 = face.area.dot(face.centre - estimate);
    const double sign = signedPyramid3 < 0 ? -1.0 : 1.0;
    const double pyramid3 = sign * signedPyramid3;
    const double pyramidBar = sumBar + centreSumBar.dot(0.75 * face.centre + 0.25 * estimate);
    centreBar[f] += 0.75 * pyramid3 * centreSumBar;
    estimateBar += 0.25 * pyramid3 * centreSumBar;
    areaBar[f] += sign * pyramidBar * (face.centre - estimate);
    centreBar[f] += sign * pyramidBar * face.area;
    estimateBar -= sign * pyramidBar * face.area;
  }
  for (std::size_t f = 0; f < faces.size(); ++f)
  {
    centreBar[f] += estimateBar / count;
  }
}
} // namespace mlsdeform
