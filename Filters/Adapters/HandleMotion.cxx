#include "Adapters/HandleMotion.h"

#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkTransform.h>

#include <algorithm>
#include <cmath>

namespace mlsvtk
{
namespace
{
constexpr double Degrees = 180.0 / M_PI;

// Rz Ry Rx of the angles (degrees) as a transform.
void rotateXYZ(vtkTransform* transform, const double rotation[3])
{
  transform->RotateX(rotation[0]);
  transform->RotateY(rotation[1]);
  transform->RotateZ(rotation[2]);
}
}

void handleMotionMatrix(const HandleMotion& motion, const double pivot[3], double matrix[16])
{
  vtkNew<vtkTransform> map;
  map->PostMultiply();
  map->Translate(-pivot[0], -pivot[1], -pivot[2]);
  map->Scale(motion.scale);
  rotateXYZ(map, motion.rotation);
  map->Translate(pivot[0] + motion.translation[0], pivot[1] + motion.translation[1], pivot[2] + motion.translation[2]);
  vtkMatrix4x4::DeepCopy(matrix, map->GetMatrix());
}

HandleMotion handleMotion(const double matrix[16], const double pivot[3])
{
  HandleMotion motion;
  double R[3][3]; // the columns of the linear part, normalized: Rz Ry Rx
  for (int j = 0; j < 3; ++j)
  {
    motion.scale[j] = std::sqrt(matrix[j] * matrix[j] + matrix[4 + j] * matrix[4 + j] + matrix[8 + j] * matrix[8 + j]);
    for (int i = 0; i < 3; ++i)
    {
      R[i][j] = motion.scale[j] > 0 ? matrix[4 * i + j] / motion.scale[j] : (i == j ? 1.0 : 0.0);
    }
  }
  // Rz(c) Ry(b) Rx(a) has R[2][0] = -sin b, R[2][1] = sin a cos b, R[2][2] = cos a cos b,
  // R[1][0] = sin c cos b, R[0][0] = cos c cos b
  const double b = std::asin(std::clamp(-R[2][0], -1.0, 1.0));
  double a = 0, c = 0;
  if (std::abs(R[2][0]) < 1 - 1e-12)
  {
    a = std::atan2(R[2][1], R[2][2]);
    c = std::atan2(R[1][0], R[0][0]);
  }
  else // cos b = 0: only a - c (or a + c) is defined; a = 0, and R[0][1] = -sin c, R[1][1] = cos c
  {
    c = std::atan2(-R[0][1], R[1][1]);
  }
  motion.rotation[0] = a * Degrees;
  motion.rotation[1] = b * Degrees;
  motion.rotation[2] = c * Degrees;
  // x' = A x + p = pivot + t + A (x - pivot) gives t = p + A pivot - pivot
  for (int i = 0; i < 3; ++i)
  {
    motion.translation[i] = matrix[4 * i + 3] - pivot[i];
    for (int j = 0; j < 3; ++j)
    {
      motion.translation[i] += matrix[4 * i + j] * pivot[j];
    }
  }
  return motion;
}

BoxTransform boxTransform(const HandleMotion& motion, const double pivot[3])
{
  BoxTransform box;
  double matrix[16];
  handleMotionMatrix(motion, pivot, matrix);
  vtkNew<vtkTransform> rotation;
  rotation->PostMultiply();
  rotateXYZ(rotation, motion.rotation);
  rotation->GetOrientation(box.rotation); // VTK's Z, X, Y angles of the same rotation
  for (int i = 0; i < 3; ++i)
  {
    box.position[i] = matrix[4 * i + 3];
    box.scale[i] = motion.scale[i];
  }
  return box;
}
} // namespace mlsvtk
