// A handle region's motion, as the designer sets it (typed or dragged): scale along the axes,
// then rotate about X, then Y, then Z, both about a pivot, then translate,
//   x' = pivot + translation + Rz Ry Rx S (x - pivot).
// ParaView's box widget describes the same affine map its own way (vtkPVTransform: about the
// origin, rotations in VTK's Z, X, Y order); both conversions live here so that the filter and
// the GUI widget agree.
#pragma once

#include "MLSDeformFiltersModule.h"

namespace mlsvtk
{
struct MLSDEFORMFILTERS_EXPORT HandleMotion
{
  double translation[3] = { 0, 0, 0 };
  double rotation[3] = { 0, 0, 0 }; // degrees, about X, then Y, then Z
  double scale[3] = { 1, 1, 1 };
};

/// The affine map of the motion about pivot as a row-major 4x4 matrix.
MLSDEFORMFILTERS_EXPORT void handleMotionMatrix(const HandleMotion& motion, const double pivot[3], double matrix[16]);

/// The motion about pivot whose map is matrix (row-major 4x4): a rotation times positive scales
/// along the axes, then a translation (what the box widget produces). Scales are the column
/// lengths; at gimbal lock (rotation about Y of +-90 degrees) the rotation about X is 0.
MLSDEFORMFILTERS_EXPORT HandleMotion handleMotion(const double matrix[16], const double pivot[3]);

/// The box widget's Position, Rotation and Scale (vtkPVTransform: translate, rotate about Z, X,
/// then Y in degrees, scale, all about the origin) that give the same map as motion about pivot.
struct MLSDEFORMFILTERS_EXPORT BoxTransform
{
  double position[3] = { 0, 0, 0 };
  double rotation[3] = { 0, 0, 0 };
  double scale[3] = { 1, 1, 1 };
};
MLSDEFORMFILTERS_EXPORT BoxTransform boxTransform(const HandleMotion& motion, const double pivot[3]);
} // namespace mlsvtk
