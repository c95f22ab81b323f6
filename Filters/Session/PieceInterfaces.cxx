#include "Session/PieceInterfaces.h"

#include "Quality/FaceQualityAggregate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>

using namespace mlsdeform;

namespace mlsvtk
{
void PieceInterfaces::find(const std::vector<VolumeMeshQuality*>& sets, const PointOf& rest, const Collective& group)
{
  *this = PieceInterfaces();
  // every boundary face of every set and process: its key, process, set and number
  std::vector<std::int64_t> local;
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    if (sets[s])
    {
      const std::vector<std::uint64_t> keys = sets[s]->boundaryKeys();
      for (std::size_t b = 0; b < keys.size(); ++b)
      {
        local.insert(local.end(), { static_cast<std::int64_t>(keys[b]), group.rank(), static_cast<std::int64_t>(s), static_cast<std::int64_t>(b) });
      }
    }
  }
  const std::vector<std::int64_t> every = group.gather(local);
  const std::size_t count = every.size() / 4;
  std::vector<std::size_t> order(count);
  std::iota(order.begin(), order.end(), 0);
  auto entry = [&](std::size_t i) { return std::array<std::int64_t, 4>{ every[4 * i], every[4 * i + 1], every[4 * i + 2], every[4 * i + 3] }; };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return entry(a) < entry(b); });
  // keys that occur twice are pairs (the first the owner); more often, a face of three pieces
  std::vector<std::uint64_t> between;
  std::vector<std::pair<std::size_t, BoundaryFace>> faces; // this process's sides: set, face
  for (std::size_t a = 0, e = 0; a < count; a = e)
  {
    for (e = a + 1; e < count && every[4 * order[e]] == every[4 * order[a]]; ++e)
    {
    }
    if (e - a < 2)
    {
      continue;
    }
    between.push_back(static_cast<std::uint64_t>(every[4 * order[a]]));
    if (e - a > 2)
    {
      continue;
    }
    for (std::size_t k = a; k < e; ++k)
    {
      const std::array<std::int64_t, 4> x = entry(order[k]);
      if (x[1] == group.rank())
      {
        const std::size_t s = static_cast<std::size_t>(x[2]);
        Sides.push_back({ s, -1, -1, Pairs, k == a, 1 });
        faces.emplace_back(s, sets[s]->mesh().boundary[static_cast<std::size_t>(x[3])]);
      }
    }
    ++Pairs;
  }
  // each set's cells there as a small piece of their own, points numbered compactly
  Pieces.resize(sets.size());
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    std::vector<int> cells;
    for (const auto& [set, face] : faces)
    {
      if (set == s)
      {
        cells.push_back(face.owner);
      }
    }
    if (cells.empty())
    {
      continue;
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    const CellFaceList& all = sets[s]->mesh().cells;
    Piece& piece = Pieces[s];
    for (int c : cells)
    {
      for (long f = all.firstFace(c); f < all.firstFace(c + 1); ++f)
      {
        piece.ids.insert(piece.ids.end(), all.face(f), all.face(f) + all.faceSize(f));
      }
    }
    std::sort(piece.ids.begin(), piece.ids.end());
    piece.ids.erase(std::unique(piece.ids.begin(), piece.ids.end()), piece.ids.end());
    std::vector<CellFaces> compact(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c)
    {
      for (long f = all.firstFace(cells[c]); f < all.firstFace(cells[c] + 1); ++f)
      {
        std::vector<int> polygon;
        for (std::size_t k = 0; k < all.faceSize(f); ++k)
        {
          polygon.push_back(static_cast<int>(std::lower_bound(piece.ids.begin(), piece.ids.end(), all.face(f)[k]) - piece.ids.begin()));
        }
        compact[c].push_back(polygon);
      }
    }
    piece.cells = CellFaceList(compact);
    for (std::size_t i = 0; i < Sides.size(); ++i)
    {
      if (Sides[i].set == s)
      {
        const BoundaryFace& face = faces[i].second;
        Sides[i].cell = static_cast<int>(std::lower_bound(cells.begin(), cells.end(), face.owner) - cells.begin());
        Sides[i].face = piece.cells.firstFace(Sides[i].cell) + (face.face - all.firstFace(face.owner));
      }
    }
  }
  std::sort(between.begin(), between.end());
  for (VolumeMeshQuality* set : sets)
  {
    if (set)
    {
      set->leaveOutBoundaryFaces(between);
    }
  }
  // the owners' faces oriented out of their cells on the rest points, as OpenFOAM fixes a face's
  // order in the topology
  takePoints(rest);
  for (Side& side : Sides)
  {
    if (side.owner)
    {
      const Piece& piece = Pieces[side.set];
      const Vec3 P = cellGeometry(piece.points, piece.cells, side.cell).centre;
      const FaceGeometry g = faceGeometry(piece.points, piece.cells.face(side.face), piece.cells.faceSize(side.face));
      side.sign = g.area.dot(g.centre - P) < 0 ? -1 : 1;
    }
  }
}

void PieceInterfaces::takePoints(const PointOf& point)
{
  for (std::size_t s = 0; s < Pieces.size(); ++s)
  {
    Pieces[s].points.resize(Pieces[s].ids.size());
    for (std::size_t i = 0; i < Pieces[s].ids.size(); ++i)
    {
      Pieces[s].points[i] = point(s, Pieces[s].ids[i]);
    }
  }
}

const PieceInterfaces::Measures& PieceInterfaces::measure(const PointOf& point, const Collective& group)
{
  Last = Measures();
  if (Pairs == 0)
  {
    return Last;
  }
  takePoints(point);
  // the cells' centres, the non-owners' sent to the owners
  Centres.resize(Sides.size());
  std::vector<double> mine;
  for (std::size_t i = 0; i < Sides.size(); ++i)
  {
    const Piece& piece = Pieces[Sides[i].set];
    Centres[i] = cellGeometry(piece.points, piece.cells, Sides[i].cell).centre;
    if (!Sides[i].owner)
    {
      mine.insert(mine.end(), { static_cast<double>(Sides[i].pair), Centres[i].x(), Centres[i].y(), Centres[i].z() });
    }
  }
  const std::vector<double> every = group.gather(mine);
  NeighbourCentres.assign(static_cast<std::size_t>(Pairs), Vec3::Zero());
  for (std::size_t r = 0; r + 3 < every.size(); r += 4)
  {
    NeighbourCentres[static_cast<std::size_t>(every[r])] = Vec3(every[r + 1], every[r + 2], every[r + 3]);
  }
  for (std::size_t i = 0; i < Sides.size(); ++i)
  {
    const Side& side = Sides[i];
    if (side.owner)
    {
      const Piece& piece = Pieces[side.set];
      const int* ids = piece.cells.face(side.face);
      const std::size_t n = piece.cells.faceSize(side.face);
      FaceGeometry g = faceGeometry(piece.points, ids, n);
      g.area *= side.sign;
      const Vec3& N = NeighbourCentres[side.pair];
      Last.nonOrthogonality.push_back(nonOrthogonality(Centres[i], N, g.area));
      Last.skewness.push_back(skewness(Centres[i], N, g, piece.points, ids, n));
    }
  }
  return Last;
}

std::vector<PieceInterfaces::Term> PieceInterfaces::aggregateGradient(
  QualityMeasure measure, double rho, const AggregatePart& whole, const Collective& group) const
{
  std::vector<Term> terms;
  if (Pairs == 0)
  {
    return terms;
  }
  const std::vector<double>& q = measure == QualityMeasure::NonOrthogonality ? Last.nonOrthogonality : Last.skewness;
  std::vector<PointList> gradient(Pieces.size());
  for (std::size_t s = 0; s < Pieces.size(); ++s)
  {
    gradient[s].assign(Pieces[s].ids.size(), Vec3::Zero());
  }
  // the owners' faces and cells here, the derivatives along the neighbours' centres sent to them
  std::vector<double> mine;
  std::size_t k = 0;
  for (std::size_t i = 0; i < Sides.size(); ++i)
  {
    const Side& side = Sides[i];
    if (!side.owner)
    {
      continue;
    }
    const double weight = std::exp(rho * (q[k++] - whole.largest)) / whole.sum;
    if (weight >= LeastAggregateWeight)
    {
      const Piece& piece = Pieces[side.set];
      const Vec3 Nbar = addFaceMeasureGradient(piece.points, piece.cells, side.cell, side.face, side.sign, Centres[i],
        NeighbourCentres[side.pair], measure, weight, gradient[side.set]);
      mine.insert(mine.end(), { static_cast<double>(side.pair), Nbar.x(), Nbar.y(), Nbar.z() });
    }
  }
  const std::vector<double> every = group.gather(mine);
  std::vector<Vec3> centreBar(static_cast<std::size_t>(Pairs), Vec3::Zero());
  std::vector<unsigned char> weighed(static_cast<std::size_t>(Pairs), 0);
  for (std::size_t r = 0; r + 3 < every.size(); r += 4)
  {
    centreBar[static_cast<std::size_t>(every[r])] = Vec3(every[r + 1], every[r + 2], every[r + 3]);
    weighed[static_cast<std::size_t>(every[r])] = 1;
  }
  for (const Side& side : Sides)
  {
    if (!side.owner && weighed[side.pair])
    {
      const Piece& piece = Pieces[side.set];
      addCellCentreGradient(piece.points, piece.cells, side.cell, centreBar[side.pair], gradient[side.set]);
    }
  }
  for (std::size_t s = 0; s < Pieces.size(); ++s)
  {
    for (std::size_t i = 0; i < gradient[s].size(); ++i)
    {
      if (gradient[s][i] != Vec3::Zero())
      {
        terms.push_back({ s, Pieces[s].ids[i], gradient[s][i] });
      }
    }
  }
  return terms;
}
} // namespace mlsvtk
