// The faces of an OpenFOAM case's cells for the mesh quality (VolumeMeshQuality), taken from its
// polyMesh (faces, owner, neighbour: OpenFOAM's own face list) rather than matched among the
// grid's cells by their points, with the undeformed mesh's figures on the case's points, read
// ahead in a background thread while VTK's reader reads the same case (prefetchCaseFaces) or else
// while MLS Deform sets up (readCaseFacesAhead): a batch's first variant does not wait for them.
#pragma once

#include "Quality/FaceQuality.h"

#include <optional>
#include <string>
#include <vector>

class vtkUnstructuredGrid;

namespace mlsvtk
{
/// A case's cells as their faces, and the figures of its points (constant/polyMesh/points as VTK's
/// reader gives them: rounded to float), which are the undeformed mesh's where the grid has them.
struct CaseMesh
{
  mlsdeform::MeshFaces faces;
  mlsdeform::PointList points;
  std::vector<int> orientation;     // faceOrientation on points
  mlsdeform::FaceMeasures measures; // the summary of points (no per-face values)
  mlsdeform::FaceWorkspace work;    // its buffers, for the next measures (first touched ahead)
};

/// Starts reading the faces of the case folder casePath (its constant/polyMesh) in a background
/// thread, for the next caseFaces of that case, unless a read of that case is under way or not yet
/// taken; a read of another case not yet taken is dropped.
void prefetchCaseFaces(const std::string& casePath);

/// prefetchCaseFaces when grid may be the case's mesh (as many points and cells, cells that do
/// not change in time: read from the files' headers); otherwise, or when they cannot be read,
/// nothing.
void readCaseFacesAhead(const std::string& casePath, vtkUnstructuredGrid* grid);

/// The faces of the case folder casePath when grid is that case's mesh as OpenFOAM numbers it:
/// the case's cells are constant/polyMesh's at every time (no time folder has faces of its own),
/// the grid has as many points and cells, and each of its cells has exactly the points of the
/// case's cell of that number. Otherwise, or when a file cannot be read, nothing: the caller
/// matches the faces itself. Takes the case's faces read ahead when there are (and drops those
/// read ahead for another case).
std::optional<CaseMesh> caseFaces(const std::string& casePath, vtkUnstructuredGrid* grid);
} // namespace mlsvtk
