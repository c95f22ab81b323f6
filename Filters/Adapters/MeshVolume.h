// The volume of a volume mesh's 3D cells and its exact gradient at the mesh's points, each cell as
// its solver measures it: a linear or quadratic tetrahedron, hexahedron or wedge as CalculiX
// integrates the isoparametric element (Structural/ShapeSensitivity.h meshVolume: a deck's mass is
// its density times this), any other cell (a CFD mesh's polyhedra, pyramids, prisms) as OpenFOAM
// does, by pyramids on its faces about the average face centre (Quality/FaceQuality.h
// cellGeometry, differentiated by FaceQualityAggregate.h's adjoints). For design constraints on a
// part's volume or mass (DesignConstraints.addMeshVolumeConstraint).
#pragma once

#include "Common/CoreTypes.h"

#include <vector>

class vtkUnstructuredGrid;

namespace mlsvtk
{
/// The volume of the grid's 3D cells with selected[cell] set (empty: every one) on `points` (one
/// per grid point: the deformed positions), and, when gradient is given (one entry per point),
/// dV/dX added to it. The elements are summed in parallel, each point's terms in cell order: the
/// same bits for any thread count.
double meshVolume(vtkUnstructuredGrid* grid, const mlsdeform::PointList& points, const std::vector<char>& selected,
  mlsdeform::PointList* gradient);
} // namespace mlsvtk
