// VTK point sets as the core's point lists: the point-set leaves of a dataset or composite, their
// points concatenated, and point lists back as VTK point clouds.
#pragma once

#include "Common/CoreTypes.h"
#include <vtkSmartPointer.h>
#include <string>
#include <utility>
#include <vector>

class vtkDataObject;
class vtkDoubleArray;
class vtkPointSet;
class vtkPolyData;

namespace mlsvtk
{
/// The point sets in a vtkPointSet or composite dataset, in traversal order. Other leaf types
/// (image data, ...) are skipped and counted in skipped.
std::vector<vtkPointSet*> pointSets(vtkDataObject* input, int* skipped = nullptr);

/// The set's points into out (GetNumberOfPoints() of them), from a float or double array without a
/// virtual call per point.
void copyPoints(vtkPointSet* set, mlsdeform::Vec3* out);

/// All points of the point sets, concatenated.
mlsdeform::PointList points(const std::vector<vtkPointSet*>& sets);

/// The cells of dimension 2 of the point sets (polygons, triangles, quads, strips) as triangles
/// (vtkCell::Triangulate): an array of 9 coordinates per triangle, named name.
vtkSmartPointer<vtkDoubleArray> triangleCorners(const std::vector<vtkPointSet*>& sets, const char* name);

/// Points (with vertices) carrying the given point arrays, one value per point.
vtkSmartPointer<vtkPolyData> pointCloud(const mlsdeform::PointList& points,
  const std::vector<std::pair<std::string, const std::vector<double>*>>& arrays);
} // namespace mlsvtk
