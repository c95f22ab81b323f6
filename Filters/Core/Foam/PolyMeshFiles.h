// OpenFOAM polyMesh list files, in ascii or binary format, plain or gzip-compressed (name.gz). A
// points file (constant/polyMesh/points): a FoamFile header and a vectorField of double (or, with
// arch "scalar=32", float) coordinates, read so that the same format can be written back with new
// coordinates; labelList files (owner, neighbour, pointProcAddressing); the faces
// (faceCompactList, or an ascii faceList); the boundary's patches with their groups.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mlsfoam
{
struct FoamPointsFile
{
  std::string path;        // the file read: .../points or .../points.gz
  std::string header;      // everything before the point count, written back unchanged
  bool binary = false;     // format binary
  bool compressed = false; // points.gz
  int scalarBytes = 8;     // from arch "scalar=64" (8) or "scalar=32" (4)
  std::vector<double> xyz; // 3 coordinates per point
  std::size_t size() const { return xyz.size() / 3; }
};

/// Reads polyMesh/points or polyMesh/points.gz of the polyMesh directory. Throws
/// std::runtime_error with the file and the reason when there is none or it cannot be parsed.
FoamPointsFile readFoamPoints(const std::string& polyMeshDirectory);

/// Reads the labelList file name (or name.gz) of a polyMesh directory, e.g. a processor's
/// pointProcAddressing (for each of its points, the point of the whole mesh it is). Throws
/// std::runtime_error with the file and the reason.
std::vector<std::int64_t> readFoamLabels(const std::string& polyMeshDirectory, const std::string& name);

/// readFoamLabels as int (a label beyond int's range is an error): the owner and neighbour lists.
std::vector<int> readFoamIndices(const std::string& polyMeshDirectory, const std::string& name);

/// A polyMesh's faces: face f's points are points[start[f]] .. points[start[f + 1] - 1], in
/// OpenFOAM's order (their normal by the right-hand rule points out of the face's owner).
struct FoamFaces
{
  std::vector<int> start{ 0 };
  std::vector<int> points;
  std::size_t size() const { return start.size() - 1; }
};

/// Reads polyMesh/faces (or faces.gz) of the polyMesh directory. Throws std::runtime_error with
/// the file and the reason.
FoamFaces readFoamFaces(const std::string& polyMeshDirectory);

/// A patch of a polyMesh's boundary: its name, type and groups (its inGroups list, which OpenFOAM
/// utilities and dictionaries name patches by: wall, motorBikeGroup).
struct FoamPatch
{
  std::string name;
  std::string type;
  std::vector<std::string> groups;
};

/// Reads polyMesh/boundary (or boundary.gz) of the polyMesh directory: its patches in order.
/// Throws std::runtime_error with the file and the reason.
std::vector<FoamPatch> readFoamBoundary(const std::string& polyMeshDirectory);

/// The file directory/name, or directory/name.gz when only that exists; "" when neither does.
std::string foamFile(const std::string& directory, const std::string& name);

/// Whether a folder name is a time (a number: "0", "0.5", "1e-05"), as OpenFOAM names time folders.
bool isTimeName(const std::string& name);

/// The mesh's size as OpenFOAM notes it in the owner file's header ("nPoints:435962
/// nCells:370338 ..."), read without the lists; -1 where there is no such file or note.
struct FoamMeshSize
{
  long long points = -1;
  long long cells = -1;
};
FoamMeshSize readFoamMeshSize(const std::string& polyMeshDirectory);

/// Writes the points xyz (3 per point) into directory/points (or points.gz when the original
/// was compressed) with the original's header and format. Ascii coordinates are written in
/// the shortest form that reads back as the same double. Throws std::runtime_error.
void writeFoamPoints(const std::string& directory, const FoamPointsFile& original, const std::vector<double>& xyz);
} // namespace mlsfoam
