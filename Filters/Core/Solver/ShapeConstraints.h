// Geometric constraints in the deformation (paper section 6): for each constrained point set t
// the constraint energy gamma_c * weight_t / n_t * |C_t (x_t + Phi_t w) - C_t P_t(x_t + Phi_t w)|^2
// of eq. 15, with C_t either the mean-centering matrix of Shape-Up (eq. 16) or the sparse
// formulation of section 6.1 (row i: x_i - x_p with p the point closest to the mean). With the
// projections P_t held fixed this is quadratic in w: its normal matrix joins eq. 17 once, and
// each local/global iteration only needs new projections and a new right-hand side.
//
// The two C_t are different penalties: C_s^T C_s = C_m^T C_m + n u u^T with u = e_p - 1/n, so
// the sparse one adds n |r_p - rbar|^2 (r = y - P). At a finite gamma_c that term pulls the
// pivot's residual towards the mean and, since the pivot is not exactly at the mean, tilts planes
// and turns feature lines away from the energy minimum (by 2e-3 of the diagonal in a test). The
// sparse right-hand side therefore also carries n u u^T Phi_t w of the current w (a deferred
// correction): the matrix stays the sparse one of section 6.1, and the fixed point of the
// iteration is exactly the mean-centered one.
//
// The slip constraint (a ground, symmetry, inlet or outlet plane of a CFD domain) is not a shape
// but a place: its points stay on their rest plane and slide freely within it. Its C_t is the
// identity (a translation normal to the plane must cost), and P_t projects onto the rest plane,
// so the local step asks for the tangential part of the current displacement only. A slip plane
// normal to a coordinate axis a is exact and needs no iteration: its term asks d_a = 0 at its
// points, which touches the system of coordinate a only (axisNormal(a)).
//
// The symmetric constraint (a car's or a hull's symmetry plane) is about displacements too: the
// region's displacement field is the mirror image of itself in a plane the user gives, so that
// an asymmetric handle motion gives a symmetric variant. Its C_t is the identity as well (a
// translation across the plane is not symmetric), and P_t averages each point's displacement with
// the mirrored displacement of its mirror image.
//
// The coplanar constraint keeps several regions on one common plane (wheel contact patches, a
// split flange): every Coplanar set of one group is projected onto the least-squares plane of all
// of the group's current positions, and its C_t is the identity too (a set's offset from the
// common plane must cost, which a mean-centered C_t would not see).
//
// The distance constraint keeps two regions of one group at their rest distance (a wheelbase, a
// bolt spacing): between their centroids, or along an axis. P_t translates both sets along that
// direction, the smaller set more (the smallest move of all their points), and C_t = I.
//
// The offset constraint keeps a region at least a bound away from a fixed reference surface (a
// minimum wall thickness between an outer skin and an inner part): P_t moves the points that came
// nearer, or crossed, back to the bound on their rest side and leaves the others (a lower bound,
// active only where violated); C_t = I.
#pragma once

#include "Solver/ConstraintProjections.h"
#include "Basis/ShapeFunctions.h"

#include <memory>

namespace mlsdeform
{
enum class ConstraintType
{
  Planarity,
  Circularity,
  Cylinder,
  FeatureLine,
  Rigid,
  Slip,
  Symmetric,
  Coplanar,
  Distance,
  Offset
};
/// One row per constraint type: its name and the fewest points its projection needs. A new type
/// is a row here, a value above and its projection (ConstraintProjections.h).
struct ConstraintTypeRow
{
  const char* name;
  std::size_t fewestPoints;
};
inline constexpr ConstraintTypeRow ConstraintTypes[] = {
  { "Planarity", 3 }, { "Circularity", 3 }, { "Cylinder", 6 }, { "FeatureLine", 2 }, { "Rigid", 2 }, { "Slip", 3 }, { "Symmetric", 1 }, { "Coplanar", 1 },
  { "Distance", 1 }, { "Offset", 1 },
};
static_assert(sizeof(ConstraintTypes) / sizeof(ConstraintTypes[0]) == static_cast<std::size_t>(ConstraintType::Offset) + 1,
  "one row per constraint type");
inline const char* constraintName(ConstraintType type)
{
  return ConstraintTypes[static_cast<int>(type)].name;
}
inline std::size_t fewestPoints(ConstraintType type)
{
  return ConstraintTypes[static_cast<int>(type)].fewestPoints;
}

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
  Plane mirror; // a Symmetric set's plane
  int group = 0; // the Coplanar sets of one group share a plane (at least 3 points together); a Distance group has two sets
  Vec3 axis = Vec3::Zero(); // a Distance set's axis (zero: the distance between the centroids)
  double minimumDistance = 0; // an Offset set's bound (0: its least distance at rest)
  std::shared_ptr<const ReferenceSurface> reference; // an Offset set's reference surface
};

/// Whether a constraint measures its points' places, not their shape: C_t = I (Slip, Symmetric,
/// Coplanar, Distance, Offset).
inline bool measuresPlaces(ConstraintType type)
{
  return type == ConstraintType::Slip || type == ConstraintType::Symmetric || type == ConstraintType::Coplanar ||
    type == ConstraintType::Distance || type == ConstraintType::Offset;
}

class ShapeConstraints
{
public:
  /// Phi and C Phi at each set's positions. Throws InvalidInputException for a set with too
  /// few points for its type or positions outside every support.
  ShapeConstraints(const ShapeFunctions& basis, const std::vector<ShapeConstraint>& constraints, ConstraintFormulation formulation);

  /// sum_t weight_t / n_t (C_t Phi_t)^T (C_t Phi_t), the constraint part of eq. 17 (k x k),
  /// over the sets other than axis-normal slip planes.
  const SparseMatrix& normalMatrix() const { return Normal; }

  /// sum weight_t / n_t Phi_t^T Phi_t over the slip planes normal to axis a: the part of eq. 17
  /// for coordinate a only (the target is d_a = 0); zero when there is none.
  const SparseMatrix& axisNormal(int a) const { return AxisNormals[a]; }
  bool hasAxisSlips() const { return AxisSlips; }

  /// Whether the local/global iteration is needed: any set other than an axis-normal slip.
  bool iterative() const { return Iterative; }

  /// Every set's current positions y_t = x_t + Phi_t w.
  std::vector<PointList> positions(const Displacements& w) const;

  /// The largest distance of a constrained point between two lists of every set's positions.
  static double largestDistance(const std::vector<PointList>& a, const std::vector<PointList>& b);

  /// The cylinder fits' axes of the rest positions (zero for the other types): where the local
  /// steps of one solve start.
  std::vector<Vec3> restAxes() const;

  /// The local step: every set's projection of its current positions. axes (one per set, from
  /// restAxes) start the cylinder fits and return their axes; the iteration that owns them
  /// carries them from step to step, so that a solve depends on its inputs only.
  std::vector<PointList> project(const std::vector<PointList>& positions, std::vector<Vec3>& axes) const;

  /// The constraint part of the right-hand side of eq. 17 for the projections of the current
  /// positions: sum_t weight_t / n_t Phi_t^T v_t with v_t = C_m^T C_m (P_t - x_t), plus, for the
  /// sparse formulation, the deferred correction n u u^T (y_t - x_t) (see above).
  Displacements rightHandSide(const std::vector<PointList>& positions, const std::vector<PointList>& projections) const;

  /// Per set: the largest distance between two lists of positions (e.g. from the projections).
  static std::vector<double> largestDistances(const std::vector<PointList>& a, const std::vector<PointList>& b);


private:
  struct Set
  {
    ShapeConstraint constraint;
    long begin = 0;                   // its first row in Subspace: Phi_t = rows begin .. begin + n_t
    int pivot = 0;                    // p of the sparse formulation
    double scale = 1;                 // weight_t / n_t
    Vec3 restAxis = Vec3::Zero();     // the cylinder fit's axis of the rest positions
    Plane restPlane;                  // the slip constraint's plane of the rest positions
    int slipAxis = -1;                // the axis a slip plane is normal to, or -1
    std::vector<int> partner;         // a Symmetric set's mirror image of each point
    long other = -1;                  // a Distance set's partner set
    double distance = 0;              // a Distance group's rest distance (along the axis, first set to second)
    std::vector<double> side;         // an Offset set's side of the reference surface per point
    double bound = 0;                 // an Offset set's least distance from it
  };

  std::vector<Set> Sets;
  SparseRowMatrix Subspace;           // Phi at every set's positions, the sets in turn
  SparseRowMatrix TransposedSubspace; // its transpose, for the right-hand side of every iteration
  ConstraintFormulation Formulation;
  SparseMatrix Normal;
  SparseMatrix AxisNormals[3];
  bool AxisSlips = false, Iterative = false;
};
} // namespace mlsdeform
