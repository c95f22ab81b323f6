// Conversion of VTK inputs (a vtkPointSet or a composite of point sets) into the core's types:
// the leaves in traversal order, their points concatenated, and the domain to sample (2D cells as
// the surface, 3D cells as the volume). Not wrapped; used by the MLS filters.
#pragma once

#include "SpaceDeformation.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkDataObject;
class vtkPointSet;
class vtkPolyData;

namespace mlsgeometry
{
/// The point sets in a vtkPointSet or composite dataset, in traversal order. Other leaf types
/// (image data, ...) are skipped and counted in skipped.
std::vector<vtkPointSet*> pointSets(vtkDataObject* input, int* skipped = nullptr);

/// All points of the point sets, concatenated.
mlsdeform::PointList points(const std::vector<vtkPointSet*>& sets);

/// Surface triangles and volume tetrahedra of the point sets (indices into points(sets)). When
/// there are 3D cells but no 2D cells, the boundary faces of the 3D cells are the surface.
mlsdeform::SamplingDomain samplingDomain(const std::vector<vtkPointSet*>& sets);

/// A signature of the point coordinates (array identity and modification time) that changes
/// whenever the points do.
std::string pointsSignature(const std::vector<vtkPointSet*>& sets);

/// A signature of the cells (array identity and modification time) that changes whenever the
/// connectivity does.
std::string cellsSignature(const std::vector<vtkPointSet*>& sets);

/// Points (with vertices) carrying the given point arrays, one value per point.
vtkSmartPointer<vtkPolyData> pointCloud(const mlsdeform::PointList& points,
  const std::vector<std::pair<std::string, const std::vector<double>*>>& arrays);

/// Reports progress of the core to a VTK algorithm (client is a vtkAlgorithm*).
void reportProgress(void* algorithm, double fraction);
}
