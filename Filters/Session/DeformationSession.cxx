#include "Session/DeformationSession.h"

#include "Adapters/AlgorithmProgress.h"
#include "Adapters/PointSets.h"
#include "Common/BoundingBox.h"
#include "Solver/LinearizedFixedPoint.h"
#include "Vocabulary/FieldNames.h"
#include "Vocabulary/RegionRoles.h"

#include <vtkAlgorithm.h>
#include <vtkLogger.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <string>

using namespace mlsdeform;

namespace mlsvtk
{
namespace
{
// The key of the regions of one kind (constraints or targets).
std::vector<RegionKey> regionKeys(const std::vector<RegionInput>& regions, bool constraints)
{
  std::vector<RegionKey> keys;
  for (const RegionInput& r : regions)
  {
    if (isConstraint(r.role) == constraints)
    {
      keys.push_back({ r.version, r.role, r.weight,
        { r.mirror.point.x(), r.mirror.point.y(), r.mirror.point.z(), r.mirror.normal.x(), r.mirror.normal.y(), r.mirror.normal.z(),
          static_cast<double>(r.group), r.axis.x(), r.axis.y(), r.axis.z(), r.minimumDistance } });
    }
  }
  return keys;
}

// Exact constraints are met when the alternating projections move no point by more than this
// fraction of the diagonal: 1e-11, a hundredth of the issue's 1e-9, so that the central
// differences of two intersections (step 1e-4 of the length) carry 1e-7 relative noise at most.
constexpr double IntersectionTolerance = 1e-11;
// Alternating projections converge linearly; a feasible scene of the suite needs tens to
// hundreds of steps. More than this: the sets and targets are taken to contradict each other.
constexpr int MaxIntersectionSteps = 20000;

std::vector<PointDisplacementsView> viewsOf(const std::vector<PointDisplacements>& sets)
{
  std::vector<PointDisplacementsView> views;
  for (const PointDisplacements& d : sets)
  {
    views.emplace_back(d.data(), d.rows(), 3);
  }
  return views;
}
}

DeformationSession::DeformationSession(vtkAlgorithm* owner)
  : Owner(owner)
{
}

void DeformationSession::readInputs(const std::vector<vtkPointSet*>& sets, vtkInformationVector* regions, int extrusionAxis,
  const Collective& group)
{
  if (extrusionAxis < -1 || extrusionAxis > 2)
  {
    throw InvalidInputException("the extrusion axis must be -1 (none), 0, 1 or 2 (x, y, z), not " + std::to_string(extrusionAxis));
  }
  if (extrusionAxis != Extruded.axis)
  {
    // Phi is evaluated at other positions: as if the points had changed
    Extruded.axis = extrusionAxis;
    PointsVersion = NextVersion++;
    Diagonal = -1;
    Targets.invalidate();
    Constraints.invalidate();
    SlipKey.invalidate();
  }
  agree(group, [&] {
    Stamp stamp = pointsStamp(sets);
    if (stamp != PointsStamp)
    {
      PointList read = points(sets);
      requireFinite(read, "input points");
      if (read != Points || PointsVersion < 0)
      {
        Points = std::move(read);
        PointsVersion = NextVersion++;
        Diagonal = -1;
      }
      PointsStamp = std::move(stamp);
    }
    readRegions(regions, Regions);
  });
  if (!group.any(!Points.empty()))
  {
    throw InvalidInputException("the input has no points");
  }
  if (group.any(Diagonal < 0))
  {
    const BoundingBox box = boundingBox(Points, group);
    Diagonal = box.size().norm();
    Extruded.middle = Extruded.active() ? 0.5 * (box.lower[Extruded.axis] + box.upper[Extruded.axis]) : 0.0;
  }
  gatherRegions(Regions, NextVersion, group);
  Design = designTable(Regions);
  std::vector<RegionKey> slipKey;
  for (const RegionInput& r : Regions)
  {
    slipKey.push_back({ r.version, r.role, 0.0, {} }); // a plane depends on the positions and the role only
  }
  if (SlipKey.stale(slipKey))
  {
    SlipKey.invalidate();
    Slips = slipPlanes(Regions);
    if (Extruded.active())
    {
      Slips.push_back(Extruded.slide());
    }
    SlipKey.built(std::move(slipKey));
  }
}

bool DeformationSession::updateSubspace(const SubspaceDependencies& dependencies, const std::vector<vtkPointSet*>& sets,
  const std::function<std::unique_ptr<SpaceDeformation>()>& build, const Collective& group)
{
  SubspaceKey key{ dependencies, dependencies.geometry ? cellsStamp(sets) : Stamp(), dependencies.geometry ? PointsVersion : 0 };
  if (!group.any(!Model || Subspace.stale(key)))
  {
    return false;
  }
  // everything built on the subspace goes first (its memory too)
  Subspace.invalidate();
  PointRowsKey.invalidate();
  Targets.invalidate();
  Constraints.invalidate();
  Model.reset();
  PointRows = RowBlocks();
  PointsProductIsLast = false;
  Model = build();
  Subspace.built(std::move(key));
  ++Counts.subspace;
  checkAbort(Owner, group);
  return true;
}

void DeformationSession::updatePointRows(const Collective& group)
{
  agree(group, [&] {
    if (PointRowsKey.stale(PointsVersion))
    {
      vtkLogScopeF(TRACE, "MLS Deform: Phi at the input points");
      PointRowsKey.invalidate();
      Targets.invalidate(); // the region rows are views of these rows
      std::vector<int> outside;
      PointList projected;
      PointRows = subspaceBlocks(Model->basis(), Extruded.evaluated(Points, projected), &outside, progressOf(Owner, 0.6, 0.9, group));
      if (!outside.empty())
      {
        throw InvalidInputException(std::to_string(outside.size()) + " input point(s) lie outside every MLS support (e.g. point " +
          std::to_string(outside[0]) + "): the samples do not cover the input; sample this input or raise Cover");
      }
      PointRowsKey.built(PointsVersion);
      ++Counts.pointRows;
    }
  });
  checkAbort(Owner, group);
}

void DeformationSession::updateTargets()
{
  TargetsKey key{ regionKeys(Regions, false) };
  if (!Targets.stale(key))
  {
    return;
  }
  Targets.invalidate();
  std::vector<DirichletRegion> targets;
  PointList positions;
  for (const RegionInput& r : Regions)
  {
    if (!isConstraint(r.role))
    {
      PointList projected;
      targets.push_back({ Extruded.evaluated(r.gathered.positions, projected), r.weight });
      positions.insert(positions.end(), r.gathered.positions.begin(), r.gathered.positions.end());
    }
  }
  // a region's points are usually input points too (a patch of the mesh): their rows of Phi are
  // stage 2's, viewed rather than evaluated again or copied
  TargetRows = positionsAmong(Points, positions);
  Model->setRegions(targets, { &PointRows, TargetRows });
  Targets.built(std::move(key));
  ++Counts.targets;
}

void DeformationSession::updateExactTargets(double radius, bool exactConstraints, const Collective& group)
{
  const bool constrained = exactConstraints && radius > 0 && std::count(SetIsSlip.begin(), SetIsSlip.end(), 0) > 0;
  ExactTargetsKey key{ PointsVersion, { regionKeys(Regions, false) }, constrained ? regionKeys(Regions, true) : std::vector<RegionKey>(),
    radius };
  if (!ExactKey.stale(key))
  {
    return;
  }
  ExactKey.invalidate();
  Exact.clear();
  SiteSets.clear();
  ++ExactBuilds;
  if (radius > 0)
  {
    vtkLogScopeF(TRACE, "MLS Deform: exact targets' blend");
    agree(group, [&] {
      PointList targets, projected;
      for (const RegionInput& r : Regions)
      {
        if (!isConstraint(r.role))
        {
          const PointList& evaluated = Extruded.evaluated(r.gathered.positions, projected);
          targets.insert(targets.end(), evaluated.begin(), evaluated.end());
        }
      }
      // the shape constraints' positions (a Slip set is kept exactly by the slide)
      PointList constrainedPositions;
      if (constrained)
      {
        for (std::size_t t = 0; t + 1 < SetBegin.size(); ++t)
        {
          if (!SetIsSlip[t])
          {
            constrainedPositions.insert(constrainedPositions.end(), ConstraintPositions.begin() + SetBegin[t], ConstraintPositions.begin() + SetBegin[t + 1]);
          }
        }
      }
      Exact.build(targets, constrainedPositions, Extruded.evaluated(Points, projected), radius * Diagonal, progressOf(Owner, 0.9, 0.95, group));
      long i = 0;
      SiteSets.assign(constrained ? SetBegin.size() - 1 : 0, {});
      for (std::size_t t = 0; t < SiteSets.size(); ++t)
      {
        for (long a = SetBegin[t]; a < SetBegin[t + 1] && !SetIsSlip[t]; ++a)
        {
          SiteSets[t].push_back(Exact.constrainedSite(i++));
        }
      }
    });
  }
  ExactKey.built(std::move(key));
  checkAbort(Owner, group);
}

void DeformationSession::updateConstraints(ConstraintFormulation formulation)
{
  ConstraintsKey key{ regionKeys(Regions, true), formulation };
  if (!Constraints.stale(key))
  {
    return;
  }
  Constraints.invalidate();
  std::vector<ShapeConstraint> shapes;
  for (const RegionInput* r : iteratedConstraints())
  {
    if (Extruded.active() && r->role != roles::Slip)
    {
      throw InvalidInputException(std::string("a ") + regionRole(r->role).name +
        " region in a 2D (extruded) deformation: only Handle, Fixed and Slip regions are supported there");
    }
    addConstraintSets(*r, shapes);
  }
  Model->setConstraints(shapes, formulation);
  ConstraintPositions.clear();
  SetBegin.assign(1, 0);
  SetIsSlip.clear();
  for (const ShapeConstraint& shape : shapes)
  {
    ConstraintPositions.insert(ConstraintPositions.end(), shape.positions.begin(), shape.positions.end());
    SetBegin.push_back(static_cast<long>(ConstraintPositions.size()));
    SetIsSlip.push_back(shape.type == ConstraintType::Slip);
  }
  Constraints.built(std::move(key));
  ++Counts.constraints;
}

std::vector<const RegionInput*> DeformationSession::iteratedConstraints() const
{
  std::vector<const RegionInput*> iterated;
  for (const RegionInput& r : Regions)
  {
    // a front or back plane of an extruded case is kept exactly by the extrusion's slide
    if (isConstraint(r.role) && !(r.role == roles::Slip && Extruded.normalPlane(r.gathered.positions, 1e-6 * Diagonal)))
    {
      iterated.push_back(&r);
    }
  }
  return iterated;
}

bool DeformationSession::updateFactorization(const EnergyWeights& weights)
{
  if (Model->isFactorizedFor(weights))
  {
    return false;
  }
  vtkLogScopeF(TRACE, "MLS Deform: factorization");
  Model->factorize(weights);
  ++Counts.factorization;
  return true;
}

SpaceDeformation::Solution DeformationSession::solve(const IterationSettings& settings, const Collective& group)
{
  vtkLogScopeF(TRACE, "MLS Deform: solve");
  Last = SpaceDeformation::Solution();
  LastField = PointField();
  ++Solutions;
  TargetConflicts.clear();
  ConstraintConflicts.clear();
  Intersected = false;
  const std::vector<PointDisplacementsView> prescribed = gatherPrescribed(Regions, Prescribed, group);
  PointsProductIsLast = false;
  Last = Model->solve(prescribed, settings);
  LastField.w = Last.w;
  if (Exact.active())
  {
    if (!dragged()) // the whole output follows (movingSets)
    {
      PointsProduct.resize(static_cast<long>(Points.size()), 3);
      multiplyRows(PointRows, Last.w, 0, PointRows.rows(), PointsProduct.data());
      PointsProductIsLast = true;
    }
    const PointDisplacements reached =
      Model->regionDisplacements(Last.w, PointsProductIsLast ? KnownProduct{ &TargetRows, PointsProduct.data() } : KnownProduct{});
    LastField.r = Exact.residuals(prescribed, reached);
    measureTargets(prescribed, Exact.misses(prescribed, reached, LastField.r));
    if (Exact.hasConstraintSites())
    {
      const IntersectionResult z = intersect(Last.w, LastField.r);
      Intersected = z.converged;
      if (Intersected)
      {
        constraintResiduals(z, Last.w, LastField.r);
      }
      else
      {
        reportConflicts(z);
      }
    }
    // (Slip sets alone: the slide puts their points on their planes; the iteration's residuals stand)
    if (std::count(SetIsSlip.begin(), SetIsSlip.end(), 0) > 0)
    {
      measureConstraints();
    }
  }
  if (Design.size() > 0)
  {
    Derivatives.gather(Regions, Design, group);
  }
  ++Counts.solve;
  return Last;
}

void DeformationSession::measureTargets(const std::vector<PointDisplacementsView>& prescribed, const std::vector<double>& miss)
{
  std::size_t i = 0, r = 0;
  for (std::size_t c = 0; c < Regions.size(); ++c)
  {
    if (isConstraint(Regions[c].role))
    {
      continue;
    }
    double squared = 0, largest = 0;
    for (long j = 0; j < prescribed[r].rows(); ++j, ++i)
    {
      squared += miss[i] * miss[i];
      largest = std::max(largest, miss[i]);
    }
    Last.rmsResidual[r] = std::sqrt(squared / prescribed[r].rows());
    // a target of exact arithmetic misses by round-off of |dbar| at most
    if (largest > 1e-9 * Diagonal)
    {
      TargetConflicts += (TargetConflicts.empty() ? "" : ", ") + std::string("#") + std::to_string(c) + " (" +
        regionRole(Regions[c].role).name + ", up to " + std::to_string(largest) + ")";
    }
    ++r;
  }
}

void DeformationSession::measureConstraints()
{
  if (ConstraintBlend.exactBuild != ExactBuilds || ConstraintBlend.constraints != Counts.constraints)
  {
    PointList projected;
    ConstraintBlend.rows = Exact.rowsAt(Extruded.evaluated(ConstraintPositions, projected), positionsAmong(Points, ConstraintPositions));
    ConstraintBlend.exactBuild = ExactBuilds;
    ConstraintBlend.constraints = Counts.constraints;
  }
  PointDisplacements added(ConstraintBlend.rows.rows(), 3);
  multiplyRows(ConstraintBlend.rows, LastField.r, 0, ConstraintBlend.rows.rows(), added.data());
  Last.constraintResidual = Model->constraintResiduals(Last.w, added, Last.axes);
}

IntersectionResult DeformationSession::intersect(const Displacements& w, const PointDisplacements& r) const
{
  const std::vector<PointList> y = Model->constraintPositions(w);
  PointList start = Exact.sites();
  std::vector<char> pinned(start.size(), 0);
  std::vector<std::vector<long>> sets;
  std::vector<std::size_t> modelSet; // of each set of the intersection
  for (std::size_t t = 0; t < SiteSets.size(); ++t)
  {
    if (SiteSets[t].empty())
    {
      continue;
    }
    for (std::size_t a = 0; a < SiteSets[t].size(); ++a)
    {
      const long s = SiteSets[t][a];
      pinned[s] = Exact.isTarget(s);
      start[s] = y[t][a] + (pinned[s] ? Vec3(r.row(s).transpose()) : Vec3::Zero());
    }
    sets.push_back(SiteSets[t]);
    modelSet.push_back(t);
  }
  const auto project = [&](const std::vector<PointList>& positions) {
    std::vector<PointList> all(SiteSets.size()); // a Slip set empty: it projects nothing
    for (std::size_t k = 0; k < sets.size(); ++k)
    {
      all[modelSet[k]] = positions[k];
    }
    const std::vector<PointList> projected = Model->projectConstraints(all, Last.axes);
    std::vector<PointList> ours;
    for (std::size_t t : modelSet)
    {
      ours.push_back(projected[t]);
    }
    return ours;
  };
  IntersectionResult z = projectOntoIntersection(sets, project, start, pinned, IntersectionTolerance * Diagonal, MaxIntersectionSteps);
  // per model set, for reporting
  std::vector<double> gap(SiteSets.size(), 0.0);
  for (std::size_t k = 0; k < sets.size(); ++k)
  {
    gap[modelSet[k]] = z.gap[k];
  }
  z.gap = std::move(gap);
  return z;
}

void DeformationSession::constraintResiduals(const IntersectionResult& z, const Displacements& w, PointDisplacements& r) const
{
  const std::vector<PointList> y = Model->constraintPositions(w);
  for (std::size_t t = 0; t < SiteSets.size(); ++t)
  {
    for (std::size_t a = 0; a < SiteSets[t].size(); ++a)
    {
      const long s = SiteSets[t][a];
      if (!Exact.isTarget(s))
      {
        r.row(s) = (z.positions[s] - y[t][a]).transpose();
      }
    }
  }
}

void DeformationSession::reportConflicts(const IntersectionResult& z)
{
  // the sets of a constraint region are consecutive in the model (addConstraintSets)
  std::size_t t = 0;
  for (const RegionInput* r : iteratedConstraints())
  {
    double gap = 0;
    for (int k = 0; k < r->gathered.setCount; ++k, ++t)
    {
      gap = std::max(gap, t < z.gap.size() ? z.gap[t] : 0.0);
    }
    if (gap > IntersectionTolerance * Diagonal)
    {
      const long c = r - Regions.data();
      ConstraintConflicts += (ConstraintConflicts.empty() ? "" : ", ") + std::string("#") + std::to_string(c) + " (" +
        regionRole(r->role).name + ", gap " + std::to_string(gap) + ")";
    }
  }
}

double DeformationSession::targetCorrection() const
{
  return LastField.r.rows() > 0 ? LastField.r.rowwise().norm().maxCoeff() : 0.0;
}

PointField DeformationSession::tangent(const std::vector<double>& seeds) const
{
  const std::vector<PointDisplacements> along = Derivatives.along(seeds);
  const std::vector<PointDisplacementsView> views = viewsOf(along);
  PointField t;
  t.w = Model->tangent(views, Last);
  if (Exact.active())
  {
    t.r = Exact.residuals(views, Model->regionDisplacements(t.w));
  }
  if (Intersected)
  {
    // the intersection's derivative by central differences along (dw, dr at the targets), the
    // step of the constraint iteration's (LinearizedFixedPoint.h), noise 1e-7 (see above)
    const std::vector<PointList> y0 = Model->constraintPositions(Displacements::Zero(t.w.rows(), 3));
    const std::vector<PointList> dy = Model->constraintPositions(t.w);
    double largest = t.r.cwiseAbs().maxCoeff();
    for (std::size_t s = 0; s < dy.size(); ++s)
    {
      for (std::size_t a = 0; a < dy[s].size(); ++a)
      {
        largest = std::max(largest, (dy[s][a] - y0[s][a]).cwiseAbs().maxCoeff());
      }
    }
    const double h = centralDifferenceStep(Model->lengthScale(), largest);
    if (h > 0)
    {
      const IntersectionResult plus = intersect(Last.w + h * t.w, LastField.r + h * t.r);
      const IntersectionResult minus = intersect(Last.w - h * t.w, LastField.r - h * t.r);
      if (!plus.converged || !minus.converged)
      {
        throw SolverException("the exact constraints' derivative: the constraints no longer meet a step of 1e-4 of the model's length "
                              "away; the design is at a conflict of its constraints");
      }
      IntersectionResult dz = plus;
      for (std::size_t s = 0; s < dz.positions.size(); ++s)
      {
        dz.positions[s] = (plus.positions[s] - minus.positions[s]) / (2 * h) + Exact.sites()[s];
      }
      constraintResiduals(dz, t.w, t.r); // dz - Phi dw (positions offset by x, as constraintPositions)
    }
  }
  return t;
}

void DeformationSession::displacement(const PointField& field, long offset, long n, double* out) const
{
  if (&field == &LastField && PointsProductIsLast)
  {
    std::copy_n(PointsProduct.data() + 3 * offset, 3 * n, out);
  }
  else
  {
    multiplyRows(PointRows, field.w, offset, offset + n, out);
  }
  if (field.r.rows() > 0)
  {
    Exact.add(field.r, offset, offset + n, out);
  }
  slideOnPlanes(Slips, Points, offset, n, out);
}

void DeformationSession::writeSensitivities(const std::vector<vtkPointSet*>& outSets, const std::vector<char>& moving)
{
  for (std::size_t v = 0; v < Design.size(); ++v)
  {
    std::vector<double> seeds(Design.size(), 0.0);
    seeds[v] = 1;
    const PointField t = tangent(seeds);
    long offset = 0;
    for (std::size_t s = 0; s < outSets.size(); ++s)
    {
      vtkPointSet* set = outSets[s];
      const vtkIdType n = set->GetNumberOfPoints();
      if (!moving[s])
      {
        offset += n;
        continue;
      }
      vtkNew<vtkDoubleArray> derivative;
      derivative->SetName((fields::SensitivityPrefix + Design.names[v]).c_str());
      derivative->SetNumberOfComponents(3);
      derivative->SetNumberOfTuples(n);
      if (n > 0)
      {
        displacement(t, offset, n, derivative->GetPointer(0));
      }
      set->GetPointData()->AddArray(derivative);
      Output.addDerived(s, derivative); // kept with the points (a drag's, a cancel's)
      offset += n;
    }
  }
}

std::vector<double> DeformationSession::objectiveSensitivity(const std::vector<double>& gradient, const Collective& group, std::string& method)
{
  return objectiveSensitivities(sparseGradient(gradient), group, method).front();
}

std::vector<std::vector<double>> DeformationSession::objectiveSensitivities(
  SparseGradients gradients, const Collective& group, std::string& method)
{
  // g -> S^T g (the slide's transpose), then H = Phi^T S^T g over the canonical positions
  slideRowsOnPlanes(Slips, Points, gradients.rows, gradients.values.data(), true);
  if (PointOrderOf != PointsVersion)
  {
    PointOrder = positionOrder(Points);
    PointOrderOf = PointsVersion;
  }
  const GatheredGradients g = gatherGradients(Points, PointOrder, gradients, group);
  const GradientRows& at = gradientRows(g.positions, g.among);
  std::vector<PointField> tangents; // the nonlinear solution's: one per variable, shared by the functions
  if (!Model->isLinear())
  {
    method = "implicit differentiation of the constraint iteration's fixed point (GMRES, the projections' derivatives by central "
             "differences): one tangent per variable";
    for (std::size_t v = 0; v < Design.size(); ++v)
    {
      std::vector<double> seeds(Design.size(), 0.0);
      seeds[v] = 1;
      tangents.push_back(tangent(seeds));
    }
  }
  else
  {
    method = "exact: one back-substitution for dJ/d(dbar), independent of the number of variables";
  }
  // dJ = (Phi^T g) . dw + h . dr for each function (ExactTargets.h; h = 0 for the penalty solution)
  const std::vector<PointDisplacements> products = multiplyTransposedEach(at.rows, g.values);
  const std::vector<PointDisplacements> pulled = Exact.active() ? Exact.pull(at.blend, g.values) : std::vector<PointDisplacements>();
  std::vector<std::vector<double>> out;
  for (std::size_t f = 0; f < g.values.functions(); ++f)
  {
    const Displacements H = products[f];
    const PointDisplacements h = Exact.active() ? pulled[f] : PointDisplacements();
    if (Model->isLinear())
    {
      // = (Phi^T g - Phi_T^T e) . dw + e . d(dbar): one back-substitution
      const PointDisplacements e = h.rows() > 0 ? Exact.targetShare(h) : PointDisplacements();
      PointDisplacements dJdTargets = Model->prescribedGradient(e.rows() > 0 ? Displacements(H - Model->regionTransposed(e)) : H);
      if (e.rows() > 0)
      {
        dJdTargets += e;
      }
      out.push_back(Derivatives.contract(dJdTargets));
      continue;
    }
    std::vector<double> dJdp(Design.size(), 0.0);
    for (std::size_t v = 0; v < Design.size(); ++v)
    {
      dJdp[v] = (H.array() * tangents[v].w.array()).sum() + (h.rows() > 0 ? (h.array() * tangents[v].r.array()).sum() : 0.0);
    }
    out.push_back(dJdp);
  }
  return out;
}

const DeformationSession::GradientRows& DeformationSession::gradientRows(const PointList& positions, const std::vector<long>& among)
{
  const auto current = [&](const GradientRows& r) {
    return r.subspace == Counts.subspace && r.points == PointsVersion && r.exactBuild == ExactBuilds && r.positions == positions;
  };
  // the entry found, or else the least recently used, moved to the front
  auto found = std::find_if(Gradients.begin(), Gradients.end(), current);
  if (found == Gradients.end())
  {
    found = Gradients.end() - 1; // the least recently used, made anew
  }
  std::rotate(Gradients.begin(), found, found + 1);
  GradientRows& r = Gradients[0];
  if (!current(r))
  {
    // rows at input points are stage 2's (3b's), viewed (the same bits as evaluating them); only
    // summed over (multiplyTransposed), so not sorted by where they are stored
    PointList projected;
    const PointList& evaluated = Extruded.evaluated(positions, projected);
    r.rows = gatherRows(Model->basis(), evaluated, { &PointRows, among }, nullptr, {}, false);
    r.blend = Exact.active() ? Exact.rowsAt(evaluated, among, false) : GatheredRows();
    r.positions = positions;
    r.subspace = Counts.subspace;
    r.points = PointsVersion;
    r.exactBuild = ExactBuilds;
  }
  return r;
}

void DeformationSession::deformedPoints(double* out) const
{
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "points as packed doubles");
  if (DeformedOf == Solutions && Deformed.size() == Points.size())
  {
    std::copy_n(Deformed.empty() ? nullptr : Deformed.front().data(), 3 * Deformed.size(), out);
    return;
  }
  const long n = static_cast<long>(Points.size());
  displacement(LastField, 0, n, out); // d(x), as writeOutput computes it
  for (long i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      out[3 * i + c] += Points[i][c];
    }
  }
}

const PointList& DeformationSession::deformedPoints()
{
  if (DeformedOf != Solutions || Deformed.size() != Points.size())
  {
    Deformed.resize(Points.size());
    if (!Deformed.empty())
    {
      deformedPoints(Deformed.front().data());
    }
    DeformedOf = Solutions;
  }
  return Deformed;
}

MeshQualityReport::Aggregate DeformationSession::qualityAggregate(
  QualityMeasure measure, double rho, const Collective& group, std::vector<double>* gradient)
{
  return Quality.aggregate(deformedPoints(), Solutions, measure, rho, group, gradient);
}

bool DeformationSession::dragged() const
{
  return std::any_of(Regions.begin(), Regions.end(), [](const RegionInput& r) { return r.dragging; });
}

std::vector<char> DeformationSession::movingSets(const std::vector<vtkPointSet*>& sets) const
{
  const auto isSurface = [](vtkPointSet* set) { return vtkPolyData::SafeDownCast(set) != nullptr; };
  if (!dragged() || std::all_of(sets.begin(), sets.end(), isSurface) || std::none_of(sets.begin(), sets.end(), isSurface))
  {
    return std::vector<char>(sets.size(), 1);
  }
  std::vector<char> moving;
  for (vtkPointSet* set : sets)
  {
    moving.push_back(isSurface(set) ? 1 : 0);
  }
  return moving;
}

void DeformationSession::writeOutput(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets,
  const std::vector<char>& moving)
{
  vtkLogScopeF(TRACE, "MLS Deform: output points");
  Output.write(inSets, outSets, Points, [&](long offset, long n, double* out) { displacement(LastField, offset, n, out); }, moving);
}

void DeformationSession::reportQuality(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets,
  vtkFieldData* field, const std::string& casePath, bool femSource, const Collective& group)
{
  vtkLogScopeF(TRACE, "MLS Deform: mesh quality report");
  Quality.report(inSets, outSets, field, casePath, femSource, group, Owner);
  checkAbort(Owner, group);
}
} // namespace mlsvtk
