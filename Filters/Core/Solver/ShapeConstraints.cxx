#include "Solver/ShapeConstraints.h"

#include "Solver/ConstraintProjections.h"
#include "Sampling/Sampling.h"
#include "Basis/SubspaceOperators.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mlsdeform
{
ShapeConstraints::ShapeConstraints(const ShapeFunctions& basis, const std::vector<ShapeConstraint>& constraints, ConstraintFormulation formulation)
  : Formulation(formulation)
  , Normal(basis.size(), basis.size())
{
  auto which = [&](std::size_t t) { return std::string(constraintName(constraints[t].type)) + " constraint " + std::to_string(t); };
  PointList all; // every set's positions in turn: Phi of all of them in one evaluation
  for (std::size_t t = 0; t < constraints.size(); ++t)
  {
    const ShapeConstraint& c = constraints[t];
    if (c.positions.size() < fewestPoints(c.type))
    {
      throw InvalidInputException(which(t) + " has " + std::to_string(c.positions.size()) + " point(s); it needs at least " +
        std::to_string(fewestPoints(c.type)));
    }
    requireFinite(c.positions, (which(t) + " positions").c_str());
    all.insert(all.end(), c.positions.begin(), c.positions.end());
  }
  std::map<int, std::size_t> coplanar; // points per Coplanar group
  for (const ShapeConstraint& c : constraints)
  {
    coplanar[c.group] += c.type == ConstraintType::Coplanar ? c.positions.size() : 0;
  }
  for (const auto& [group, count] : coplanar)
  {
    if (count > 0 && count < 3)
    {
      throw InvalidInputException("Coplanar group " + std::to_string(group) + " has " + std::to_string(count) +
        " point(s) in all its regions; a common plane needs at least 3");
    }
  }
  std::map<int, std::vector<std::size_t>> distanceGroups; // the sets of each Distance group
  for (std::size_t t = 0; t < constraints.size(); ++t)
  {
    if (constraints[t].type == ConstraintType::Distance)
    {
      distanceGroups[constraints[t].group].push_back(t);
    }
  }
  for (const auto& [group, sets] : distanceGroups)
  {
    if (sets.size() != 2)
    {
      throw InvalidInputException("Distance group " + std::to_string(group) + " has " + std::to_string(sets.size()) +
        " point set(s); it keeps the distance of exactly two (one region each, without CellSets)");
    }
    if (constraints[sets[0]].axis != constraints[sets[1]].axis)
    {
      throw InvalidInputException("the two regions of Distance group " + std::to_string(group) + " have different axes");
    }
  }
  std::vector<int> outside;
  Subspace = subspaceMatrix(basis, all, &outside);
  std::vector<long> begins; // each set's first row in Subspace
  long rows = 0;
  for (const ShapeConstraint& c : constraints)
  {
    begins.push_back(rows);
    rows += static_cast<long>(c.positions.size());
  }
  if (!outside.empty())
  {
    const std::size_t t = std::upper_bound(begins.begin(), begins.end(), static_cast<long>(outside.front())) - begins.begin() - 1;
    throw InvalidInputException(which(t) + ": " + std::to_string(outside.size()) + " position(s) lie outside every MLS support");
  }
  TransposedSubspace = Subspace.transpose();
  // sqrt(weight_t / n_t) C_t Phi_t of every set stacked, one stack per normal matrix (Normal,
  // AxisNormals[a]): each is then one product, sum_t weight_t / n_t (C_t Phi_t)^T (C_t Phi_t).
  std::vector<Eigen::Triplet<double>> stacks[4];
  long stackRows[4] = { 0, 0, 0, 0 };
  for (std::size_t t = 0; t < constraints.size(); ++t)
  {
    const ShapeConstraint& c = constraints[t];
    Set set;
    set.constraint = c;
    set.begin = begins[t];
    const long n = static_cast<long>(c.positions.size());
    const Vec3 mean = centroid(c.positions);
    for (long i = 1; i < n; ++i)
    {
      if ((c.positions[i] - mean).squaredNorm() < (c.positions[set.pivot] - mean).squaredNorm())
      {
        set.pivot = static_cast<int>(i);
      }
    }
    if (c.type == ConstraintType::Cylinder)
    {
      projectToCylinder(c.positions, set.restAxis); // a zero axis: the fit searches all directions
    }
    if (c.type == ConstraintType::Symmetric)
    {
      // mirror images within round-off of float coordinates (1e-6 of the set's extent)
      set.partner = mirrorPartners(c.positions, c.mirror, 1e-6 * boundingBox(c.positions).size().norm());
      const long missing = std::count(set.partner.begin(), set.partner.end(), -1);
      if (missing > 0)
      {
        throw InvalidInputException(which(t) + ": " + std::to_string(missing) + " of its " + std::to_string(n) +
          " points have no mirror image among its points: select a region that is symmetric about the plane");
      }
    }
    if (c.type == ConstraintType::Distance)
    {
      const std::vector<std::size_t>& pair = distanceGroups.at(c.group);
      set.other = static_cast<long>(pair[0] == t ? pair[1] : pair[0]);
      const Vec3 axis = c.axis.squaredNorm() > 0 ? Vec3(c.axis.normalized()) : Vec3::Zero();
      set.constraint.axis = axis;
      const Vec3 offset = centroid(constraints[pair[1]].positions) - centroid(constraints[pair[0]].positions);
      set.distance = axis.squaredNorm() > 0 ? offset.dot(axis) : offset.norm();
      if (axis.squaredNorm() == 0 && !(set.distance > 0))
      {
        throw InvalidInputException(which(t) + ": the two regions of Distance group " + std::to_string(c.group) +
          " have one centroid; give an axis or select regions apart");
      }
    }
    if (c.type == ConstraintType::Offset)
    {
      if (!c.reference)
      {
        throw InvalidInputException(which(t) + " has no reference surface");
      }
      double least = std::numeric_limits<double>::infinity();
      for (const Vec3& p : c.positions)
      {
        const ReferenceSurface::Nearest q = c.reference->nearest(p);
        set.side.push_back((p - q.point).dot(q.normal) < 0 ? -1.0 : 1.0);
        least = std::min(least, q.distance);
      }
      set.bound = c.minimumDistance > 0 ? c.minimumDistance : least;
      if (!(set.bound > 0))
      {
        throw InvalidInputException(which(t) + ": a point lies on the reference surface at rest; give a Minimum Distance");
      }
    }
    if (c.type == ConstraintType::Slip)
    {
      set.restPlane = fitPlane(c.positions);
      for (int a = 0; a < 3; ++a)
      {
        set.slipAxis = std::abs(set.restPlane.normal[a]) == 1 ? a : set.slipAxis;
      }
    }
    set.scale = c.weight / n;
    // C_t Phi_t, row by row, scaled by sqrt(scale)
    const int stack = set.slipAxis >= 0 ? 1 + set.slipAxis : 0;
    std::vector<Eigen::Triplet<double>>& entries = stacks[stack];
    long& row = stackRows[stack];
    const double root = std::sqrt(set.scale);
    auto addRow = [&](long i, double sign) {
      for (SparseRowMatrix::InnerIterator it(Subspace, set.begin + i); it; ++it)
      {
        entries.emplace_back(row, it.col(), sign * root * it.value());
      }
    };
    // 1^T Phi_t / n, the mean row of the mean-centered formulation: dense over the set's samples.
    Eigen::SparseVector<double> meanRow(Subspace.cols());
    if (formulation == ConstraintFormulation::MeanCentered && !measuresPlaces(c.type))
    {
      const Eigen::VectorXd dense = Subspace.middleRows(set.begin, n).transpose() * Eigen::VectorXd::Constant(n, 1.0 / n);
      meanRow = dense.sparseView();
    }
    for (long i = 0; i < n; ++i)
    {
      if (measuresPlaces(c.type))
      {
        addRow(i, 1.0); // x_i itself: C_t = I
      }
      else if (formulation == ConstraintFormulation::Sparse)
      {
        if (i == set.pivot)
        {
          continue;
        }
        addRow(i, 1.0); // x_i - x_p (section 6.1)
        addRow(set.pivot, -1.0);
      }
      else
      {
        addRow(i, 1.0); // x_i - mean (eq. 16)
        for (Eigen::SparseVector<double>::InnerIterator it(meanRow); it; ++it)
        {
          entries.emplace_back(row, it.index(), -root * it.value());
        }
      }
      ++row;
    }
    AxisSlips = AxisSlips || set.slipAxis >= 0;
    Iterative = Iterative || set.slipAxis < 0;
    Sets.push_back(std::move(set));
  }
  for (int stack = 0; stack < 4; ++stack)
  {
    SparseRowMatrix stacked(stackRows[stack], static_cast<long>(basis.size()));
    stacked.setFromTriplets(stacks[stack].begin(), stacks[stack].end());
    SparseMatrix& normal = stack == 0 ? Normal : AxisNormals[stack - 1];
    normal = SparseMatrix(stacked.transpose() * stacked);
  }
}

std::vector<PointList> ShapeConstraints::positions(const Displacements& w) const
{
  // Phi w at every set's positions in one pass (not one per set: thousands of per-cell sets)
  std::vector<double> d(3 * static_cast<std::size_t>(Subspace.rows()));
  multiplyRows(Subspace, w, 0, Subspace.rows(), d.data());
  std::vector<PointList> out;
  for (const Set& set : Sets)
  {
    PointList y = set.constraint.positions;
    for (std::size_t i = 0; i < y.size(); ++i)
    {
      y[i] += Vec3(&d[3 * (set.begin + static_cast<long>(i))]);
    }
    out.push_back(std::move(y));
  }
  return out;
}

std::vector<Vec3> ShapeConstraints::restAxes() const
{
  std::vector<Vec3> axes;
  for (const Set& set : Sets)
  {
    axes.push_back(set.restAxis);
  }
  return axes;
}

std::vector<PointList> ShapeConstraints::project(const std::vector<PointList>& positions, std::vector<Vec3>& axes) const
{
  // a Coplanar group's common plane: the least-squares plane of all its current positions
  std::map<int, PointList> groupPositions;
  for (std::size_t t = 0; t < Sets.size(); ++t)
  {
    if (Sets[t].constraint.type == ConstraintType::Coplanar)
    {
      PointList& all = groupPositions[Sets[t].constraint.group];
      all.insert(all.end(), positions[t].begin(), positions[t].end());
    }
  }
  std::map<int, Plane> groupPlanes;
  for (const auto& [group, all] : groupPositions)
  {
    groupPlanes[group] = fitPlane(all);
  }
  // a Distance group's translations: the first set's, and the second's from it
  std::vector<Vec3> translations(Sets.size(), Vec3::Zero());
  for (std::size_t t = 0; t < Sets.size(); ++t)
  {
    const Set& set = Sets[t];
    if (set.constraint.type == ConstraintType::Distance && static_cast<long>(t) < set.other)
    {
      const PointList& second = positions[set.other];
      translations[t] = distanceTranslation(positions[t], second, set.constraint.axis, set.distance);
      translations[set.other] = -translations[t] * static_cast<double>(positions[t].size()) / static_cast<double>(second.size());
    }
  }
  // each set on its own: in parallel over the sets, the same result on any number of threads
  std::vector<PointList> projections(Sets.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (long t = 0; t < static_cast<long>(Sets.size()); ++t)
  {
    const Set& set = Sets[t];
    const PointList& y = positions[t];
    const PointList& rest = set.constraint.positions;
    switch (set.constraint.type)
    {
      case ConstraintType::Planarity:
        projections[t] = projectToPlane(y);
        break;
      case ConstraintType::Circularity:
        projections[t] = projectToCircle(y);
        break;
      case ConstraintType::Cylinder:
        projections[t] = projectToCylinder(y, axes[t]);
        break;
      case ConstraintType::FeatureLine:
        projections[t] = projectToSimilarity(rest, y);
        break;
      case ConstraintType::Rigid:
        projections[t] = projectToRigid(rest, y);
        break;
      case ConstraintType::Slip:
        projections[t] = projectTo(set.restPlane, y);
        break;
      case ConstraintType::Symmetric:
        projections[t] = projectToSymmetric(rest, y, set.partner, set.constraint.mirror);
        break;
      case ConstraintType::Coplanar:
        projections[t] = projectTo(groupPlanes.at(set.constraint.group), y);
        break;
      case ConstraintType::Distance:
        projections[t] = y;
        for (Vec3& p : projections[t])
        {
          p += translations[t];
        }
        break;
      case ConstraintType::Offset:
        projections[t] = projectOutside(*set.constraint.reference, y, set.side, set.bound);
        break;
    }
  }
  return projections;
}

Displacements ShapeConstraints::rightHandSide(const std::vector<PointList>& positions, const std::vector<PointList>& projections) const
{
  // sum_t scale_t Phi_t^T v_t as one product Phi^T V over the stacked sets (V: every set's
  // scale_t v_t in its rows; zero for axis-normal slip planes, whose target d_a = 0 adds nothing)
  Displacements V = Displacements::Zero(Subspace.rows(), 3);
  for (std::size_t t = 0; t < Sets.size(); ++t)
  {
    const Set& set = Sets[t];
    if (set.slipAxis >= 0)
    {
      continue;
    }
    const PointList& rest = set.constraint.positions;
    const long n = static_cast<long>(rest.size());
    // v = C_m^T C_m d with d = P_t - x_t, the displacement the projection asks for: d - mean(d).
    // (C^T C d computed on points, then one product with Phi_t^T: cheaper than (C Phi)^T C d.)
    auto v = V.middleRows(set.begin, n);
    for (long i = 0; i < n; ++i)
    {
      v.row(i) = (projections[t][i] - rest[i]).transpose();
    }
    if (!measuresPlaces(set.constraint.type)) // the places (measuresPlaces): C_t = I, v = P_t - x_t
    {
      const Eigen::RowVector3d mean = v.colwise().mean();
      v.rowwise() -= mean;
      if (Formulation == ConstraintFormulation::Sparse)
      {
        // + n u u^T (y - x): -delta on every point and n delta on the pivot, with delta the
        // pivot's displacement relative to the mean displacement
        Vec3 meanDisplacement = Vec3::Zero();
        for (long i = 0; i < n; ++i)
        {
          meanDisplacement += (positions[t][i] - rest[i]) / static_cast<double>(n);
        }
        const Vec3 delta = positions[t][set.pivot] - rest[set.pivot] - meanDisplacement;
        v.rowwise() -= delta.transpose();
        v.row(set.pivot) += n * delta.transpose();
      }
    }
    v *= set.scale;
  }
  return multiplyRows(TransposedSubspace, V);
}

double ShapeConstraints::largestDistance(const std::vector<PointList>& a, const std::vector<PointList>& b)
{
  const std::vector<double> distances = largestDistances(a, b);
  return distances.empty() ? 0.0 : *std::max_element(distances.begin(), distances.end());
}

std::vector<double> ShapeConstraints::largestDistances(const std::vector<PointList>& a, const std::vector<PointList>& b)
{
  std::vector<double> out;
  for (std::size_t t = 0; t < a.size(); ++t)
  {
    double largest = 0;
    for (std::size_t i = 0; i < a[t].size(); ++i)
    {
      largest = std::max(largest, (a[t][i] - b[t][i]).norm());
    }
    out.push_back(largest);
  }
  return out;
}
} // namespace mlsdeform
