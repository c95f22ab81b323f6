// SU2 native meshes (.su2, ASCII): the mesh they hold (NPOIN= points, NELEM= elements, NMARK=
// markers; several zones after NZONE= and IZONE=), and a variant: the file with only the points'
// coordinates changed.
//
// SU2 numbers points and elements from 0 in file order, and so are their ids here; a file of
// several zones numbers each zone's from 0, and its ids go on from the zone before (zone 2's point
// 0 has the id of zone 1's NPOIN), so that they are unique and each point's id is its place among
// the file's points. NELEM='s elements are the cells: SU2 writes VTK's type numbers and VTK's node
// orders (the prism's too: its 0-1-2 turns away from 3-4-5, as Gmsh writes it and as SU2's CPrism
// faces have it). Each marker is a node set (the points of its elements) named by its tag, blanks
// removed as SU2 removes them (markers of one tag are one set); a tag that several zones have is
// told apart: "tag (zone 2)". A file of several zones has an element set and a node set of each
// zone: "zone 1", "zone 2"...
//
// A point's line is "x y [z] [index...]", an element's "type point... [index]": a trailing index
// is kept and not used (SU2 ignores it). NPOIN='s optional second number (the points that a
// partition owns) is read and not used. Blank lines and '%' comments are skipped between sections;
// another keyword (AOA_OFFSET=, the FFD_ boxes...) is skipped with the lines after it, and copied
// when writing. A 2D file's points have z = 0, and its variants keep x and y.
#pragma once

#include "SourceFile.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mlsformats
{
namespace su2
{
/// A zone of the file: its points are mesh.nodeIds[firstNode..] up to the next zone's.
struct Zone
{
  int number;    // IZONE= (1 in a file of one zone)
  int dimension; // NDIME=: 2 or 3 coordinates a point
  std::size_t firstNode;
};

struct MeshFile : SourceFile
{
  std::string path;
  /// The hash of the file's bytes: a variant is not written from a file changed since.
  std::size_t hash = 0;
  std::vector<Zone> zones;
  /// One a point, in mesh.nodeIds' order: where its x's text starts in the file (y and z follow
  /// after blanks).
  std::vector<std::uint64_t> coordinates;
  /// Where the last node's coordinates end in the file.
  std::uint64_t nodesEnd = 0;

  /// The file with each point's coordinates replaced and every other byte as it was: a changed
  /// coordinate is written as its shortest text, an unchanged one keeps its text (a 2D file's z is
  /// not written). Also refuses NaN, target being the source, and a source changed since it was
  /// read.
  void writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
    bool overwrite) const override;
};

/// Reads the mesh at path. Throws FileError ("file:line: reason") for what cannot be read: a
/// malformed number, NaN, a file cut short (fewer lines than a count announces), a line outside any
/// section (more lines than announced), an element that refers to a missing point, a zone without
/// NDIME=, NPOIN= or NELEM=. An element of a type that SU2 does not have is left out with a
/// warning (mesh.warnings).
MeshFile readSu2(const std::string& path);

/// Only what writing a variant needs: the points' ids, their coordinates and where they are (no
/// elements or sets).
MeshFile readSu2Layout(const std::string& path);

/// Whether text (a file's first bytes) is an SU2 mesh: after blank lines and '%' comments, its
/// first line is NDIME= (or NZONE=, a file of several zones).
bool isSu2(const std::string& head);
} // namespace su2
} // namespace mlsformats
