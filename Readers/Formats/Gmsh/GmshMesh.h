// Gmsh meshes (.msh, MSH 2.2 and 4.1, ASCII and binary): the mesh they hold ($Nodes, $Elements,
// the physical groups of $PhysicalNames, $Entities and $PartitionedEntities), and a variant: the file
// with only the node coordinates changed.
//
// The elements of the mesh's highest dimension are its cells (a volume mesh's boundary triangles,
// lines and points are not). Every physical group is a node set (the nodes of its elements, of any
// dimension), named by $PhysicalNames or "physical <dim> <tag>"; those of the highest dimension are
// element sets too. MSH 2.2 writes an element of several physical groups once for each, on
// consecutive lines under new tags: it is read as one element, the first. Other sections ($Periodic,
// $NodeData...) are skipped when reading and copied when writing. A binary file is read in this
// machine's byte order, the one Gmsh writes.
#pragma once

#include "SourceFile.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mlsformats
{
namespace gmsh
{
struct MshFile : SourceFile
{
  std::string path;
  /// The hash of the file's bytes: a variant is not written from a file changed since.
  std::size_t hash = 0;
  bool binary = false;
  /// One a node, in mesh.nodeIds' order: where its coordinates start in the file (ASCII: x's
  /// first character, y and z follow after blanks; binary: the first of its three doubles).
  std::vector<std::uint64_t> coordinates;
  /// Where the last node's coordinates end in the file.
  std::uint64_t nodesEnd = 0;

  /// The file with each node's x, y and z replaced and every other byte as it was: ASCII writes a
  /// changed coordinate as its shortest text and keeps an unchanged one's; binary replaces the
  /// doubles in place. Also refuses NaN, target being the source, and a source changed since it
  /// was read.
  void writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
    bool overwrite) const override;
};

/// Reads the mesh at path. Throws FileError ("file:line: reason"; a binary file: the section and
/// the byte) for what cannot be read: another MSH version, a malformed number, a truncated file, a
/// duplicate node tag, an element with a missing node, NaN. An element type without a cell type
/// is left out with a warning (mesh.warnings).
MshFile readMsh(const std::string& path);

/// Only what writing a variant needs: the nodes' tags, their coordinates and where they are (no
/// elements or sets).
MshFile readMshLayout(const std::string& path);

/// Whether text (a file's first bytes) is a Gmsh mesh: it starts with "$MeshFormat".
bool isMsh(const std::string& head);
} // namespace gmsh
} // namespace mlsformats
