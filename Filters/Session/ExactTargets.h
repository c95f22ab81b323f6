// Exact targets and constraints: the output displacement is d(x) = S (Phi(x) w + B(x) r), with B
// the blend functions over the sites, the distinct positions of the Handle and Fixed regions and
// of the constrained sets (Basis/ResidualBlend.h), and r the residuals there. At a target site
// r_s = mean over the targets i at s of dbar_i - Phi(x_i) w, so that every target is met to
// round-off (targets at one position that disagree meet their mean: a conflict, reported as the
// regions' residual); at a constraint site r_s = z_s - x_s - Phi(x_s) w for the positions z on
// every constraint (Solver/ConstraintIntersection.h), or 0 (the soft solution). The penalty
// solution of eq. 14 is the special case without B.
//
// Derivatives: dX = S (Phi dw + B dr), dr at a target site the same mean of d(dbar) - Phi dw.
// Reverse mode: for g = S^T dJ/dX at gathered positions, h = B^T g per site gives
// dJ = (Phi^T g) . dw + h . dr; without constraint sites, e_i = h_s / m_s per target (m_s targets
// at site s) turns it into one back-substitution:
//   dJ = (Phi^T g - Phi_T^T e) . dw + e . d(dbar).
// B's rows at the gathered gradient's positions are evaluated on every process alike, so under
// MPI h is the serial one bitwise (DesignSensitivities.h).
#pragma once

#include "Basis/ResidualBlend.h"
#include "Basis/SubspaceOperators.h"

#include <memory>

namespace mlsvtk
{
class ExactTargets
{
public:
  /// The blend over the targets' positions (stacked over the target regions, as Phi is evaluated
  /// at them) and the constrained sets' positions (stacked over the sets; none: exact targets
  /// only) with fade radius R, and its rows at the points (as Phi is evaluated at them).
  void build(const mlsdeform::PointList& targets, const mlsdeform::PointList& constrained, const mlsdeform::PointList& points,
    double radius, const mlsdeform::Progress& progress);
  /// The penalty solution: no correction.
  void clear();
  bool active() const { return Blend != nullptr; }

  /// r per site from the prescribed displacements (one set per target region) and Phi w at the
  /// stacked targets (SpaceDeformation::regionDisplacements), 0 at the constraint sites; also the
  /// derivative's dr.
  mlsdeform::PointDisplacements residuals(
    const std::vector<mlsdeform::PointDisplacementsView>& prescribed, const mlsdeform::PointDisplacements& reached) const;

  /// The output's miss at each stacked target, |dbar_i - Phi w_i - r_s|: zero but where targets
  /// at one position disagree.
  std::vector<double> misses(const std::vector<mlsdeform::PointDisplacementsView>& prescribed, const mlsdeform::PointDisplacements& reached,
    const mlsdeform::PointDisplacements& r) const;

  /// Rows begin..end of B r added to out (3 per point).
  void add(const mlsdeform::PointDisplacements& r, long begin, long end, double* out) const;

  /// B at positions (as Phi is evaluated at them), viewed from the points' rows where
  /// among[i] names the point at positions[i] (positionsAmong); storageOrder as gatherRows'.
  mlsdeform::GatheredRows rowsAt(const mlsdeform::PointList& positions, std::vector<long> among, bool storageOrder = true) const;

  /// h_f = B^T g_f per site for each function's g_f given at the positions of rows (rowsAt).
  std::vector<mlsdeform::PointDisplacements> pull(const mlsdeform::GatheredRows& rows, const mlsdeform::SparseGradients& g) const;
  /// e (one row per stacked target) of h.
  mlsdeform::PointDisplacements targetShare(const mlsdeform::PointDisplacements& h) const;

  /// The sites' positions; whether a site holds a target; the site of each stacked constrained
  /// position.
  const mlsdeform::PointList& sites() const { return Sites; }
  bool isTarget(long site) const { return SiteCount[site] > 0; }
  long constrainedSite(long i) const { return SiteOf[Targets + i]; }
  bool hasConstraintSites() const { return static_cast<long>(SiteOf.size()) > Targets; }

private:
  std::unique_ptr<mlsdeform::ResidualBlend> Blend;
  mlsdeform::PointList Sites;
  long Targets = 0;              // stacked targets; SiteOf's further rows are the constrained positions
  std::vector<long> SiteOf;      // per stacked target, then per stacked constrained position
  std::vector<double> SiteCount; // m_s, targets at site s
  mlsdeform::RowBlocks PointRows;
};
} // namespace mlsvtk
