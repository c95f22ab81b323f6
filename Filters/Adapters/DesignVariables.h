// Design variables on a handle's motion (the global design variables of pyGeo's DVGeometry): a
// named scalar p with bounds that changes a Handle region's motion (HandleMotion.h) in one way,
// with the axis vector a (its length is the coefficient, so that one variable can move a
// symmetric pair of handles with a and -a):
//   Translate: the translation grows by p a                  (model units per unit of p)
//   Rotate:    a rotation by p |a| degrees about n = a / |a| through the pivot
//   Scale:     the scale factor along n grows by p |a|        (S + p |a| n n^T)
// With the typed motion x -> pivot + T + A (x - pivot), A = R S, the region's map is
//   x' = pivot + T + t + R_dv (A + R S_dv) (x - pivot)
// where t is the translation variables' sum, S_dv the scale variables' sum and R_dv = R_1 R_2 ...
// the rotation variables' product in their order. At p = 0 every variable's term is exactly zero
// (the typed motion is unchanged), and the derivatives below are those of this map:
//   Translate: a;  Scale: R_dv R |a| n n^T (x - pivot);  Rotate i: R_1 .. dR_i/dp .. R_m (A + R S_dv)(x - pivot).
// A Local variable (pyGeo's addLocalDV) moves no region as a body: it holds the region's control
// points (ControlPoints.h) at x + p a, a per control point, and has no axis of its own (zero);
// this map leaves it out (its derivative here is zero).
#pragma once

#include "Adapters/HandleMotion.h"
#include "Common/CoreTypes.h"

#include <string>
#include <vector>

namespace mlsvtk
{
/// One row per kind of design variable: its name (the Python layer's keyword is its lower case).
inline constexpr const char* DesignKindNames[] = { "Translate", "Rotate", "Scale", "Local" };
enum DesignKind
{
  Translate = 0,
  Rotate,
  Scale,
  Local
};

struct DesignVariable
{
  std::string name;
  int kind = Translate;
  mlsdeform::Vec3 axis = mlsdeform::Vec3::Zero(); // a: direction times coefficient (zero for Local)
  double value = 0, lower = 0, upper = 0;
};

/// Throws mlsdeform::InvalidInputException for an empty or repeated name, an unknown kind, a zero
/// or non-finite axis (a non-zero one for Local), lower > upper or a value outside its bounds.
void checkDesignVariables(const std::vector<DesignVariable>& variables);

/// A handle's map with its design variables, and its derivatives.
class DesignedMotion
{
public:
  DesignedMotion(const HandleMotion& typed, const mlsdeform::Vec3& pivot, const std::vector<DesignVariable>& variables);

  /// x' - x at x, and dx'/dp of every variable in turn (3 values each) into derivatives (may be null).
  void displace(const mlsdeform::Vec3& x, double displacement[3], double* derivatives) const;

private:
  double Matrix[16];                    // the typed motion's map (handleMotionMatrix), as before design variables
  Eigen::Matrix3d A, R;                 // the typed motion's linear part and rotation
  Eigen::Matrix3d Rdv, Sdv;             // the rotation variables' product and the scale variables' sum
  mlsdeform::Vec3 Translation, Pivot;   // the translation variables' sum
  std::vector<int> Kinds;
  std::vector<Eigen::Matrix3d> Linear;  // per variable: the matrix its derivative applies to (x - pivot), or its translation in column 0
};
} // namespace mlsvtk
