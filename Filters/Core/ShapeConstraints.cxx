#include "ShapeConstraints.h"

#include "ConstraintProjections.h"
#include "Sampling.h"
#include "SubspaceOperators.h"

#include <algorithm>
#include <cmath>

namespace mlsdeform
{
namespace
{
std::size_t minimumPoints(ConstraintType type)
{
  switch (type)
  {
    case ConstraintType::Cylinder:
      return 6;
    case ConstraintType::FeatureLine:
    case ConstraintType::Rigid:
      return 2;
    default:
      return 3;
  }
}
}

const char* constraintName(ConstraintType type)
{
  static const char* names[] = { "Planarity", "Circularity", "Cylinder", "FeatureLine", "Rigid", "Slip" };
  return names[static_cast<int>(type)];
}

ShapeConstraints::ShapeConstraints(const ShapeFunctions& basis, const std::vector<ShapeConstraint>& constraints, ConstraintFormulation formulation)
  : Formulation(formulation)
  , Normal(basis.size(), basis.size())
{
  for (SparseMatrix& A : AxisNormals)
  {
    A.resize(basis.size(), basis.size());
  }
  for (std::size_t t = 0; t < constraints.size(); ++t)
  {
    const ShapeConstraint& c = constraints[t];
    const std::string which = std::string(constraintName(c.type)) + " constraint " + std::to_string(t);
    if (c.positions.size() < minimumPoints(c.type))
    {
      throw InvalidInputException(which + " has " + std::to_string(c.positions.size()) + " point(s); it needs at least " +
        std::to_string(minimumPoints(c.type)));
    }
    requireFinite(c.positions, (which + " positions").c_str());
    Set set;
    set.constraint = c;
    std::vector<int> outside;
    set.subspace = subspaceMatrix(basis, c.positions, &outside);
    if (!outside.empty())
    {
      throw InvalidInputException(which + ": " + std::to_string(outside.size()) + " position(s) lie outside every MLS support");
    }
    const long n = static_cast<long>(c.positions.size());
    Vec3 mean = Vec3::Zero();
    for (const Vec3& p : c.positions)
    {
      mean += p / static_cast<double>(n);
    }
    for (long i = 1; i < n; ++i)
    {
      if ((c.positions[i] - mean).squaredNorm() < (c.positions[set.pivot] - mean).squaredNorm())
      {
        set.pivot = static_cast<int>(i);
      }
    }
    // C_t Phi_t, row by row, for the normal matrix.
    std::vector<Eigen::Triplet<double>> entries;
    const auto& Phi = set.subspace;
    auto addRow = [&](long row, long i, double scale) {
      for (SparseRowMatrix::InnerIterator it(Phi, i); it; ++it)
      {
        entries.emplace_back(row, it.col(), scale * it.value());
      }
    };
    // 1^T Phi_t / n, the mean row of the mean-centered formulation: dense over the set's samples.
    Eigen::SparseVector<double> meanRow(Phi.cols());
    if (formulation == ConstraintFormulation::MeanCentered && c.type != ConstraintType::Slip)
    {
      const Eigen::VectorXd dense = Phi.transpose() * Eigen::VectorXd::Constant(n, 1.0 / n);
      meanRow = dense.sparseView();
    }
    long rows = 0;
    for (long i = 0; i < n; ++i)
    {
      if (c.type == ConstraintType::Slip)
      {
        addRow(rows, i, 1.0); // x_i itself: C_t = I
      }
      else if (formulation == ConstraintFormulation::Sparse)
      {
        if (i == set.pivot)
        {
          continue;
        }
        addRow(rows, i, 1.0); // x_i - x_p (section 6.1)
        addRow(rows, set.pivot, -1.0);
      }
      else
      {
        addRow(rows, i, 1.0); // x_i - mean (eq. 16)
        for (Eigen::SparseVector<double>::InnerIterator it(meanRow); it; ++it)
        {
          entries.emplace_back(rows, it.index(), -it.value());
        }
      }
      ++rows;
    }
    set.transposedSubspace = Phi.transpose();
    if (c.type == ConstraintType::Cylinder)
    {
      projectToCylinder(c.positions, set.restAxis); // a zero axis: the fit searches all directions
    }
    if (c.type == ConstraintType::Slip)
    {
      set.restPlane = fitPlane(c.positions);
      for (int a = 0; a < 3; ++a)
      {
        set.slipAxis = std::abs(set.restPlane.normal[a]) == 1 ? a : set.slipAxis;
      }
    }
    SparseRowMatrix centeredSubspace(rows, static_cast<long>(basis.size()));
    centeredSubspace.setFromTriplets(entries.begin(), entries.end());
    set.scale = c.weight / n;
    SparseMatrix& normal = set.slipAxis >= 0 ? AxisNormals[set.slipAxis] : Normal;
    normal += SparseMatrix(set.scale * (centeredSubspace.transpose() * centeredSubspace));
    AxisSlips = AxisSlips || set.slipAxis >= 0;
    Iterative = Iterative || set.slipAxis < 0;
    Sets.push_back(std::move(set));
  }
}

PointList ShapeConstraints::positionsOf(const Set& set, const Displacements& w) const
{
  const long n = set.subspace.rows();
  std::vector<double> d(3 * n);
  multiplyRows(set.subspace, w, 0, n, d.data());
  PointList y = set.constraint.positions;
  for (long i = 0; i < n; ++i)
  {
    y[i] += Vec3(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
  }
  return y;
}

std::vector<PointList> ShapeConstraints::positions(const Displacements& w) const
{
  std::vector<PointList> out;
  for (const Set& set : Sets)
  {
    out.push_back(positionsOf(set, w));
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
  std::vector<PointList> projections;
  for (std::size_t t = 0; t < Sets.size(); ++t)
  {
    const Set& set = Sets[t];
    const PointList& y = positions[t];
    const PointList& rest = set.constraint.positions;
    switch (set.constraint.type)
    {
      case ConstraintType::Planarity:
        projections.push_back(projectToPlane(y));
        break;
      case ConstraintType::Circularity:
        projections.push_back(projectToCircle(y));
        break;
      case ConstraintType::Cylinder:
        projections.push_back(projectToCylinder(y, axes[t]));
        break;
      case ConstraintType::FeatureLine:
        projections.push_back(projectToSimilarity(rest, y));
        break;
      case ConstraintType::Rigid:
        projections.push_back(projectToRigid(rest, y));
        break;
      case ConstraintType::Slip:
        projections.push_back(projectTo(set.restPlane, y));
        break;
    }
  }
  return projections;
}

Displacements ShapeConstraints::rightHandSide(const std::vector<PointList>& positions, const std::vector<PointList>& projections) const
{
  Displacements rhs = Displacements::Zero(Normal.rows(), 3);
  for (std::size_t t = 0; t < Sets.size(); ++t)
  {
    const Set& set = Sets[t];
    const PointList& rest = set.constraint.positions;
    const long n = static_cast<long>(rest.size());
    // v = C_m^T C_m d with d = P_t - x_t, the displacement the projection asks for: d - mean(d).
    // (C^T C d computed on points, then one product with Phi_t^T: cheaper than (C Phi)^T C d.)
    Displacements v(n, 3);
    for (long i = 0; i < n; ++i)
    {
      v.row(i) = (projections[t][i] - rest[i]).transpose();
    }
    if (set.slipAxis >= 0)
    {
      continue; // its target d_a = 0 adds nothing
    }
    if (set.constraint.type == ConstraintType::Slip)
    {
      rhs += set.scale * multiplyRows(set.transposedSubspace, v); // C_t = I: v = P_t - x_t
      continue;
    }
    v.rowwise() -= v.colwise().mean();
    if (Formulation == ConstraintFormulation::Sparse)
    {
      // + n u u^T (y - x): -delta on every point and n delta on the pivot, with delta the pivot's
      // displacement relative to the mean displacement
      Vec3 meanDisplacement = Vec3::Zero();
      for (long i = 0; i < n; ++i)
      {
        meanDisplacement += (positions[t][i] - rest[i]) / static_cast<double>(n);
      }
      const Vec3 delta = positions[t][set.pivot] - rest[set.pivot] - meanDisplacement;
      v.rowwise() -= delta.transpose();
      v.row(set.pivot) += n * delta.transpose();
    }
    rhs += set.scale * multiplyRows(set.transposedSubspace, v);
  }
  return rhs;
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
