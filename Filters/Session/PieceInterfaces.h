// The faces where pieces of one mesh touch: blocks of a dataset, the processes' pieces (their
// ghost cells left out), cells whose points were not merged (faces of the same positions:
// boundaryKeys). Each piece has them as
// boundary faces; here they are measured as the interior faces they are, with the other piece's
// cell centre across them, as OpenFOAM measures a processor patch's faces: the verdict and the KS
// aggregates are the whole mesh's however it is split.
#pragma once

#include "Adapters/VolumeMeshQuality.h"
#include "Common/Collective.h"

#include <functional>
#include <vector>

namespace mlsvtk
{
class PieceInterfaces
{
public:
  /// A set's point (set, point id) on the points being measured.
  using PointOf = std::function<mlsdeform::Vec3(std::size_t, long)>;

  /// Finds the faces between pieces among the boundary faces of the sets (nulls have none) on
  /// every process, leaves them out of the sets' boundaries and keeps them in pairs: owned by the
  /// side of the lower process, set and face number, oriented out of its cell on the rest points
  /// (`rest`). A face that three pieces share is left out, unmeasured. Collective.
  void find(const std::vector<VolumeMeshQuality*>& sets, const PointOf& rest, const mlsdeform::Collective& group);

  /// Whether some process has such faces (the same on every process).
  bool empty() const { return Pairs == 0; }

  /// The non-orthogonality (degrees) and skewness of each pair this process owns, on `point`'s
  /// points; kept for the gradient. Collective.
  struct Measures
  {
    std::vector<double> nonOrthogonality, skewness;
  };
  const Measures& measure(const PointOf& point, const mlsdeform::Collective& group);

  /// The KS aggregate's gradient terms of the pairs' measure (weights of whole) on the last
  /// measure's points: for this process's sides, (set, point id, dKS/dX). Collective.
  struct Term
  {
    std::size_t set;
    long point;
    mlsdeform::Vec3 value;
  };
  std::vector<Term> aggregateGradient(mlsdeform::QualityMeasure measure, double rho, const mlsdeform::AggregatePart& whole,
    const mlsdeform::Collective& group) const;

private:
  // This process's side of a pair: its set, its cell and face in that set's piece below.
  struct Side
  {
    std::size_t set;
    int cell;
    long face;
    long pair;
    bool owner;
    int sign; // the face's area times sign points out of the owner's cell on the rest points
  };
  // A set's cells at the faces between pieces, with their points numbered compactly.
  struct Piece
  {
    mlsdeform::CellFaceList cells;
    std::vector<long> ids; // compact point -> the set's point id
    mlsdeform::PointList points; // on the last measure's points
  };
  void takePoints(const PointOf& point);

  long Pairs = 0;
  std::vector<Side> Sides;
  std::vector<Piece> Pieces; // per set
  std::vector<mlsdeform::Vec3> Centres;          // per side, on the last measure's points
  std::vector<mlsdeform::Vec3> NeighbourCentres; // per pair: the non-owner side's
  Measures Last;
};
} // namespace mlsvtk
