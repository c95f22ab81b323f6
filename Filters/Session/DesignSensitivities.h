// Design sensitivities: the design variables of all Handle regions as one table, the prescribed
// displacements' derivatives along them (gathered from all processes like the displacements
// themselves), and the gradient of an objective J from dJ/dX given at the output's points.
//
// Forward mode: dX/dp = S Phi dw, dw = SpaceDeformation::tangent of d(dbar)/dp, S the slide onto
// the slip planes. Reverse mode: dJ/dp = sum_i g_i . dX_i/dp = tr(H^T dw) with H = Phi^T S^T g,
// and for a linear solution dJ/dp = sum_r dJ/d(dbar_r) . d(dbar_r)/dp with dJ/d(dbar) from one
// back-substitution (SpaceDeformation::prescribedGradient): independent of the number of
// variables. Exact targets add their correction's terms to both (ExactTargets.h).
//
// Under MPI, H must equal the serial one bitwise although a process boundary's points appear on
// several processes: g is summed over the copies of a position on one process (the blocks of one
// mesh that share a point, as in the serial dataset), the positions of all processes are
// gathered into the canonical order (Common/GatheredPositions.h; a position on several processes
// counts once, with the first process's sum) and H is summed in that order on every process.
#pragma once

#include "Common/Collective.h"
#include "Common/CoreTypes.h"
#include "Session/RegionInputs.h"

#include <string>
#include <vector>

class vtkFieldData;

namespace mlsvtk
{
struct DesignTable
{
  std::vector<std::string> names; // in the order the regions name them first
  std::vector<double> values, lower, upper;
  std::size_t size() const { return names.size(); }
  /// The column of a name, or -1.
  int column(const std::string& name) const;
};

/// The design variables of the regions; throws InvalidInputException when a name has different
/// values or bounds on two regions.
DesignTable designTable(const std::vector<RegionInput>& regions);

/// The table into field data (names, values, bounds: Vocabulary/FieldNames.h).
void writeDesignTable(const DesignTable& table, vtkFieldData* field);

/// The target regions' prescribed-displacement derivatives of all processes.
class PrescribedDerivatives
{
public:
  /// Reads the regions' derivatives (every update; nothing to gather without design variables).
  void gather(const std::vector<RegionInput>& regions, const DesignTable& table, const mlsdeform::Collective& group);

  /// d(dbar)/dp along seeds (one per variable of the table): one set per target region, in the
  /// regions' gathered order (zero for a region without those variables and for Fixed regions).
  std::vector<mlsdeform::PointDisplacements> along(const std::vector<double>& seeds) const;

  /// dJ/dp per variable from dJ/d(dbar), stacked over the target regions' gathered positions.
  std::vector<double> contract(const mlsdeform::PointDisplacements& gradient) const;

private:
  std::size_t Variables = 0;
  std::vector<long> Counts;                // per target region: its gathered positions
  std::vector<std::vector<int>> Columns;   // per target region: the table column of each of its variables
  std::vector<std::vector<double>> Values; // per target region: n_r x 3 m_r, gathered
};

/// The gradients of several functions at some of this process's points (the rows).
using mlsdeform::SparseGradients;

/// One function's gradient g (3 values per point, this process's points in order) as its
/// points with a non-zero value.
SparseGradients sparseGradient(const std::vector<double>& gradient);

/// Points ordered by position (lexicographic, equal positions together): each point's rank
/// among the distinct positions, and the first point of each rank. Found once per set of points
/// (one sort of them), so that a gradient's points are ordered without a sort each time (sorting
/// the 70k points of the hull case's constraints took 12 ms of their 65 ms chain).
struct PositionOrder
{
  std::vector<int> rank;
  std::vector<long> first;
};
PositionOrder positionOrder(const mlsdeform::PointList& points);

/// The points carrying the functions' gradients, each position once with the sum of its copies
/// (per function), gathered from all processes in canonical order (see above): the positions,
/// per function its non-zero sums there (values: rows are indices into positions, ascending),
/// and per position the first of this process's points there, or -1 (another process's).
/// order: positionOrder(points).
struct GatheredGradients
{
  mlsdeform::PointList positions;
  SparseGradients values;
  std::vector<long> among;
};
GatheredGradients gatherGradients(
  const mlsdeform::PointList& points, const PositionOrder& order, const SparseGradients& gradients, const mlsdeform::Collective& group);
} // namespace mlsvtk
