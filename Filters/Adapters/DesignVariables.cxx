#include "Adapters/DesignVariables.h"

#include <Eigen/Geometry>

#include <cmath>
#include <set>

using mlsdeform::InvalidInputException;
using mlsdeform::Vec3;

namespace mlsvtk
{
namespace
{
constexpr double Radians = M_PI / 180.0;

// [n]x, the cross product with n as a matrix.
Eigen::Matrix3d cross(const Vec3& n)
{
  Eigen::Matrix3d m;
  m << 0, -n.z(), n.y(), n.z(), 0, -n.x(), -n.y(), n.x(), 0;
  return m;
}
}

void checkDesignVariables(const std::vector<DesignVariable>& variables)
{
  std::set<std::string> names;
  for (const DesignVariable& v : variables)
  {
    const std::string which = "design variable '" + v.name + "'";
    if (v.name.empty())
    {
      throw InvalidInputException("a design variable needs a name");
    }
    if (!names.insert(v.name).second)
    {
      throw InvalidInputException(which + " is defined twice on this region (one name, one variable)");
    }
    if (v.kind < Translate || v.kind > Local)
    {
      throw InvalidInputException(which + " has an unknown kind " + std::to_string(v.kind) + " (0 Translate, 1 Rotate, 2 Scale, 3 Local)");
    }
    if (v.kind == Local && v.axis != Vec3::Zero())
    {
      throw InvalidInputException(which + " is Local: its directions are its control points' (ControlPoints), its axis must be 0 0 0");
    }
    if (v.kind != Local && (!v.axis.allFinite() || !(v.axis.norm() > 0)))
    {
      throw InvalidInputException(which + " needs a non-zero, finite axis (its direction times its coefficient)");
    }
    if (!std::isfinite(v.lower) || !std::isfinite(v.upper) || v.lower > v.upper)
    {
      throw InvalidInputException(which + ": its bounds must be finite with lower <= upper (lower " + std::to_string(v.lower) +
        ", upper " + std::to_string(v.upper) + ")");
    }
    if (!(v.value >= v.lower && v.value <= v.upper))
    {
      throw InvalidInputException(which + ": the value " + std::to_string(v.value) + " is outside its bounds [" +
        std::to_string(v.lower) + ", " + std::to_string(v.upper) + "]");
    }
  }
}

DesignedMotion::DesignedMotion(const HandleMotion& typed, const Vec3& pivot, const std::vector<DesignVariable>& variables)
  : Pivot(pivot)
{
  handleMotionMatrix(typed, pivot.data(), Matrix);
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      A(i, j) = Matrix[4 * i + j];
    }
  }
  // Rz Ry Rx of the typed angles (HandleMotion.h)
  R = (Eigen::AngleAxisd(typed.rotation[2] * Radians, Vec3::UnitZ()) * Eigen::AngleAxisd(typed.rotation[1] * Radians, Vec3::UnitY()) *
    Eigen::AngleAxisd(typed.rotation[0] * Radians, Vec3::UnitX()))
        .toRotationMatrix();
  Translation.setZero();
  Sdv.setZero();
  std::vector<Eigen::Matrix3d> rotations; // R_i of the rotation variables, in order
  for (const DesignVariable& v : variables)
  {
    if (v.kind == Local)
    {
      continue;
    }
    const double c = v.axis.norm();
    const Vec3 n = v.axis / c;
    if (v.kind == Translate)
    {
      Translation += v.value * v.axis;
    }
    else if (v.kind == Scale)
    {
      Sdv += v.value * c * n * n.transpose();
    }
    else
    {
      rotations.push_back(Eigen::AngleAxisd(v.value * c * Radians, n).toRotationMatrix());
    }
  }
  Rdv.setIdentity();
  for (const Eigen::Matrix3d& Ri : rotations)
  {
    Rdv = Rdv * Ri;
  }
  const Eigen::Matrix3d B = A + R * Sdv; // applied to x - pivot before R_dv
  std::size_t rotation = 0;
  for (const DesignVariable& v : variables)
  {
    Kinds.push_back(v.kind);
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero(); // Local: no term in this map (ControlPoints.h)
    const double c = v.axis.norm();
    const Vec3 n = v.kind == Local ? Vec3::Zero() : Vec3(v.axis / c);
    if (v.kind == Translate)
    {
      M.col(0) = v.axis;
    }
    else if (v.kind == Scale)
    {
      M = Rdv * R * (c * n * n.transpose());
    }
    else if (v.kind == Rotate)
    {
      // d/dp of R_1 .. R_i .. R_m: R_i(p) = exp(p c [n]x) in radians, dR_i/dp = c [n]x R_i
      Eigen::Matrix3d before = Eigen::Matrix3d::Identity(), after = Eigen::Matrix3d::Identity();
      for (std::size_t j = 0; j < rotation; ++j)
      {
        before = before * rotations[j];
      }
      for (std::size_t j = rotation + 1; j < rotations.size(); ++j)
      {
        after = after * rotations[j];
      }
      M = before * (c * Radians * cross(n) * rotations[rotation]) * after * B;
      ++rotation;
    }
    Linear.push_back(M);
  }
}

void DesignedMotion::displace(const Vec3& x, double displacement[3], double* derivatives) const
{
  for (int c = 0; c < 3; ++c)
  {
    // the typed motion as before: (M x + t) - x
    displacement[c] = Matrix[4 * c] * x[0] + Matrix[4 * c + 1] * x[1] + Matrix[4 * c + 2] * x[2] + Matrix[4 * c + 3] - x[c];
  }
  if (Kinds.empty())
  {
    return;
  }
  const Vec3 y = x - Pivot;
  // t + R_dv (A + R S_dv) y - A y = t + R_dv R S_dv y + (R_dv - I) A y: exactly zero at p = 0
  const Vec3 designed = Translation + Rdv * (R * (Sdv * y)) + (Rdv - Eigen::Matrix3d::Identity()) * (A * y);
  for (int c = 0; c < 3; ++c)
  {
    displacement[c] += designed[c];
  }
  if (!derivatives)
  {
    return;
  }
  for (std::size_t v = 0; v < Kinds.size(); ++v)
  {
    const Vec3 d = Kinds[v] == Translate || Kinds[v] == Local ? Vec3(Linear[v].col(0)) : Vec3(Linear[v] * y);
    std::copy(d.data(), d.data() + 3, derivatives + 3 * v);
  }
}
} // namespace mlsvtk
