// Exodus II meshes (.exo, .e, .ex2, .g): the mesh they hold (coordinates, element blocks, node
// sets, side sets), read through the netCDF C library (Exodus II is a convention on netCDF: classic,
// 64-bit offset, CDF5 and netCDF-4 files alike), and a variant: the file with only the nodes'
// coordinate variables changed.
//
// Node ids are node_num_map's (the 1-based positions without it), element ids elem_num_map's. Each
// element block is an ElementBlock (its elem_type, in VTK's node order) and an element set named by
// eb_names or "block <id>"; each node set is a node set named by ns_names or "nodeset <id>"; each
// side set is a node set of its sides' nodes named by ss_names or "sideset <id>"; a name several
// sets share is told apart ("name (sideset <id>)"). Empty blocks and sets are left out. Results
// (time steps, variables), QA and info records, attributes and maps are not read, and a variant
// keeps them untouched; the coordinates are the file's own (a results file's displacements are not
// added to them, as ParaView's readers do by default).
#pragma once

#include "SourceFile.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mlsformats
{
namespace exodus
{
struct MeshFile : SourceFile
{
  std::string path;
  /// The hash of the file's bytes: a variant is not written from a file changed since.
  std::size_t hash = 0;
  /// The mesh's dimensions (num_dim: 1, 2 or 3); the coordinates beyond them are 0.
  int dimensions = 3;
  /// The coordinate variables, x first: "coordx", "coordy", "coordz" (as many as the dimensions),
  /// or an older file's one "coord" (dimensions x nodes).
  std::vector<std::string> coordinates;
  /// Whether the coordinates are floats (else doubles).
  bool floats = false;

  /// A copy of the file with its coordinate variables rewritten through netCDF, written aside and
  /// renamed into place; every other variable, attribute and dimension is as it was (a classic
  /// file's bytes too). A float file's coordinates are rounded to the nearest float (a relative
  /// change of at most 2^-24, 6e-8, for numbers above 1e-38), which keeps its unmoved ones exactly.
  /// Also refuses a coordinate beyond a float's range in a float file, a coordinate beyond the
  /// mesh's dimensions that is not 0 (a 2D mesh's z), target being the source, and a source changed
  /// since it was read.
  void writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
    bool overwrite) const override;
};

/// Reads the mesh at path. Throws FileError ("file: variable: reason") for what cannot be read: a
/// file that is not netCDF, missing coordinates, a node id twice in node_num_map, an element or a
/// side referring to a node or an element the file does not have, a side number its element does
/// not have, NaN. An element type without a cell type is left out with a warning (mesh.warnings),
/// as are the sides of a side set on such elements.
MeshFile readExodus(const std::string& path);

/// Only what writing a variant needs: the node ids and the coordinates' variables (no coordinates,
/// elements or sets).
MeshFile readExodusLayout(const std::string& path);

/// Whether head (a file's first bytes) is a netCDF file: classic ("CDF\1"), 64-bit offset
/// ("CDF\2"), CDF5 ("CDF\5") or netCDF-4 (HDF5's signature).
bool isExodus(const std::string& head);
} // namespace exodus
} // namespace mlsformats
