// Geometric constraints in the deformation (paper section 6): for each constrained point set t
// the constraint energy gamma_c * weight_t / n_t * |C_t (x_t + Phi_t w) - C_t P_t(x_t + Phi_t w)|^2
// of eq. 15, with C_t either the mean-centering matrix of Shape-Up (eq. 16) or the sparse
// formulation of section 6.1 (row i: x_i - x_p with p the point closest to the mean). With the
// projections P_t held fixed this is quadratic in w: its normal matrix joins eq. 17 once, and
// each local/global iteration only needs new projections and a new right-hand side.
#pragma once

#include "MLSBasis.h"

namespace mlsdeform
{
enum class ConstraintType
{
  Planarity,
  Circularity,
  Cylinder,
  FeatureLine,
  Rigid
};
const char* constraintName(ConstraintType type);

enum class ConstraintFormulation
{
  Sparse,      // section 6.1: two entries per row, sparse even for a set covering the mesh
  MeanCentered // eq. 16: dense over the set's samples
};

/// A constrained point set: its rest positions and relative weight.
struct ShapeConstraint
{
  ConstraintType type = ConstraintType::Planarity;
  PointList positions;
  double weight = 1.0;
};

class ShapeConstraints
{
public:
  /// Phi and C Phi at each set's positions. Throws InvalidInputException for a set with too
  /// few points for its type or positions outside every support.
  ShapeConstraints(const MLSBasis& basis, const std::vector<ShapeConstraint>& constraints, ConstraintFormulation formulation);

  /// sum_t weight_t / n_t (C_t Phi_t)^T (C_t Phi_t), the constraint part of eq. 17 (k x k).
  const SparseMatrix& normalMatrix() const { return Normal; }

  /// Every set's current positions y_t = x_t + Phi_t w.
  std::vector<PointList> positions(const Displacements& w) const;

  /// The local step: every set's projection of its current positions.
  std::vector<PointList> project(const std::vector<PointList>& positions) const;

  /// The constraint part of the right-hand side of eq. 17 for the projections:
  /// sum_t weight_t / n_t (C_t Phi_t)^T C_t (P_t - x_t).
  Displacements rightHandSide(const std::vector<PointList>& projections) const;

  /// Per set: the largest distance between two lists of positions (e.g. from the projections).
  static std::vector<double> largestDistances(const std::vector<PointList>& a, const std::vector<PointList>& b);


private:
  struct Set
  {
    ShapeConstraint constraint;
    SparseRowMatrix subspace;         // Phi_t
    SparseRowMatrix centeredSubspace; // C_t Phi_t
    int pivot = 0;                    // p of the sparse formulation
    double scale = 1;                 // weight_t / n_t
    mutable Vec3 axis = Vec3::Zero(); // the cylinder fit's last axis
  };
  PointList positionsOf(const Set& set, const Displacements& w) const;
  Displacements centered(const Set& set, const PointList& v) const; // C_t v, one row per row of C_t

  std::vector<Set> Sets;
  ConstraintFormulation Formulation;
  SparseMatrix Normal;
};
} // namespace mlsdeform
