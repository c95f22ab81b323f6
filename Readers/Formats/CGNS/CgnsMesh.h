// CGNS files (.cgns, HDF5 or ADF), read through the CGNS library: the mesh of every base and zone,
// and a variant: the file with only the grid coordinates' values changed.
//
// Node ids are unique across zones: a zone's node of (1-based) index n has the id offset + n, its
// offset being the node count of the zones before it (bases in order, zones in order); a structured
// zone's nodes are indexed i + j*ni + k*ni*nj + 1 (CGNS's order: i fastest). Element ids likewise:
// the zone's element offset + CGNS's element number (a structured zone's cells are numbered as its
// nodes are, from 1); the offset is the elements of the zones before (an unstructured zone's: its
// highest element number).
//
// Cells: the elements of the base's cell dimension, in VTK's types and node orders (a MIXED section
// gives a block of each type); a structured zone's are hexahedra (quadrangles in 2D). Elements of
// lower dimension (a volume's boundary faces) are not cells: each such section is a node set of its
// name. NGON_n and NFACE_n sections, and element types without a cell type, are left out with a
// warning (their nodes are read and move with the rest). Each boundary condition (ZoneBC) is a node
// set of its name: its points (Vertex) or the nodes of its faces or cells (FaceCenter, CellCenter,
// a structured zone's I/J/KFaceCenter, an unstructured zone's EdgeCenter and element ranges and
// lists; a structured zone's FaceCenter faces are across the index its points share); a BC of a
// family is also in the node set "family/<family name>". Each zone is an element set of its name. A name that several zones (or
// sections and BCs) have is one set: the union.
//
// Not supported (a FileError): coordinates other than CoordinateX, Y (and Z in 3D) of RealDouble or
// RealSingle, a zone without them, rind planes; a variant of coordinates linked to another file.
//
// The CGNS library reads: ParaView's (VTK::cgns, CGNS 4.2, built with MLSFORMATS_VTK_CGNS) the files
// of CGNS 3.2 to 4.x (not some of CGNS 3.0 and 3.1: a bug of CGNS 4.2 and 4.3), Debian 12's
// libcgns 3.4 those of CGNS 3 (it refuses the files of CGNS 4, ParaView's among them). It is not
// thread-safe: read and write one CGNS file at a time.
#pragma once

#include "SourceFile.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mlsformats
{
namespace cgns
{
/// A zone's grid coordinates as the file stores them.
struct Zone
{
  std::string base, name, grid; // the nodes' names: /base/name/grid/<coordinate>
  std::int64_t nodes = 0;       // its node count
  std::int64_t offset = 0;      // its nodes' ids are offset + 1 .. offset + nodes
  std::vector<std::string> coordinates; // "CoordinateX", "CoordinateY" (, "CoordinateZ")
  std::vector<bool> single;             // each coordinate's: RealSingle (else RealDouble)
};

struct MeshFile : SourceFile
{
  std::string path;
  /// The hash of the file's bytes: a variant is not written from a file changed since.
  std::size_t hash = 0;
  std::vector<Zone> zones;

  /// The file copied byte for byte, with each zone's coordinate arrays overwritten in place in their
  /// data type (the CGNS library's CGIO layer; the mid-level library's modify mode would upgrade the
  /// file's version and layout): every other node (elements, BCs, families, connectivity, flow
  /// solutions, user data) is untouched. A RealSingle coordinate is the nearest float to the new
  /// value (a relative change up to 6e-8 above 1.2e-38); a value beyond the float range is refused.
  /// A 2D file keeps x and y, and refuses a node moved off z = 0. Also refuses NaN, target being the
  /// source, and a source changed since it was read.
  void writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
    bool overwrite) const override;
};

/// Reads the mesh at path. Throws FileError (line 0, naming the base, zone, section or BC) for
/// what cannot be read: not a CGNS file (or one of a newer library), a zone without coordinates,
/// a NaN coordinate, an element or a BC that refers to a missing node or element.
MeshFile readCgns(const std::string& path);

/// Only what writing a variant needs: the zones and their node ids (no coordinates, elements or
/// sets).
MeshFile readCgnsLayout(const std::string& path);

/// Whether text (a file's first bytes) is a CGNS file's: HDF5's signature, or ADF's "ADF Database
/// Version" after 4 bytes.
bool isCgns(const std::string& head);
} // namespace cgns
} // namespace mlsformats
