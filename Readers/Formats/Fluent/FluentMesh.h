// Fluent meshes (.msh, and the mesh in a legacy case file, .cas), ASCII and binary: the mesh they
// hold (its node, face and cell zones, named by the 39 and 45 sections), and a variant: the file
// with only the node coordinates changed.
//
// A Fluent file is a list of sections "(index ...)", their numbers hexadecimal (but for the zone
// ids of the 39 and 45 sections). A binary section's index is the ASCII one's after 20 (single
// precision) or 30 (double): "(3010 (zone first last type ND)(" data ")End of Binary Section 3010)",
// its data in this machine's byte order, its integers of 32 bits. The mesh is face-based: each face
// lists its nodes and its two cells c0 and c1 (0: none), its nodes turning so that their normal
// points into c0 (in 2D: c0 is on the left of its edge). The cells are rebuilt from their faces, by
// the faces' shapes: tetrahedra, pyramids, wedges and hexahedra (triangles and quadrilaterals in
// 2D), their nodes in VTK's order. A polyhedron, a cell that hanging nodes split, and the cells of
// an inactive zone (parents of adapted cells) are left out with a warning; their nodes are read and
// move with the rest. Node ids are Fluent's node indices, element ids its cell indices. Each face
// zone but the interior ones is a node set (the nodes of its faces), each cell zone an element set,
// named as the 39 or 45 section names the zone ("zone <id>" without). Other sections (periodic
// shadow faces, face trees, a case file's settings) are skipped when reading and copied when
// writing.
#pragma once

#include "SourceFile.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mlsformats
{
namespace fluent
{
/// How a node zone's coordinates are written: as text, or as binary floats or doubles.
enum class Precision
{
  Text,
  Single,
  Double
};

/// A node zone: how its coordinates are written, and its number of nodes (consecutive in
/// mesh.nodeIds, the zones in file order).
struct NodeZone
{
  Precision precision;
  std::size_t count;
};

struct MeshFile : SourceFile
{
  std::string path;
  /// The hash of the file's bytes: a variant is not written from a file changed since.
  std::size_t hash = 0;
  /// The coordinates a node has in the file: 2 or 3.
  int dimension = 3;
  std::vector<NodeZone> nodeZones;
  /// One a node, in mesh.nodeIds' order: where its coordinates start in the file (text: x's first
  /// character, the others follow after blanks; binary: its first float or double).
  std::vector<std::uint64_t> coordinates;
  /// Where the last node's coordinates end in the file.
  std::uint64_t nodesEnd = 0;

  /// The file with each node's coordinates replaced and every other byte as it was: a text
  /// coordinate whose value changed is written as its shortest text, an unchanged one keeps its
  /// text; binary ones are replaced in place. A single-precision zone holds
  /// its moved coordinates rounded to floats (7 significant digits): one beyond a float's range is
  /// refused. A 2D mesh's z is not written. Also refuses NaN, target being the source, and a source
  /// changed since it was read.
  void writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
    bool overwrite) const override;
};

/// Reads the mesh at path. Throws FileError ("file:line: reason"; in a binary section: the section
/// and the byte) for what cannot be read: a malformed number, a truncated section, unbalanced
/// parentheses, a count the file cannot hold, a node defined twice, a face on a missing node or
/// cell, NaN. Cells that cannot be rebuilt are left out with a warning (mesh.warnings).
MeshFile readFluent(const std::string& path);

/// Only what writing a variant needs: the node ids, their coordinates and where they are (no
/// cells or sets).
MeshFile readFluentLayout(const std::string& path);

/// Whether text (a file's first bytes) is a Fluent file: after blanks, a section "(index" with a
/// decimal index.
bool isFluent(const std::string& head);
} // namespace fluent
} // namespace mlsformats
