// Abaqus/CalculiX input decks (.inp): the mesh they hold (*NODE, *ELEMENT, *NSET, *ELSET,
// *SURFACE, through *INCLUDE), and a variant: the deck and its included files with only the node
// coordinates changed.
//
// Keywords are case-insensitive; a keyword line ending in a comma continues on the next line, an
// element's nodes continue on the next lines until it has them all; "**" starts a comment.
// *INCLUDE, INPUT=name is read relative to the main deck's folder (where ccx runs). Keywords the
// mesh does not need (materials, steps, loads) are skipped when reading and copied when writing.
// Decks of parts and instances, *SYSTEM and generated nodes or elements are refused: their
// coordinates are not the *NODE lines' (a flat deck is what Abaqus writes without "parts and
// assemblies", and what CalculiX and Gmsh write).
#pragma once

#include "SourceFile.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace mlsformats
{
namespace abaqus
{
/// Where a node's coordinates are in the deck: the file, the bytes of its coordinate fields (from
/// the first's start to the last's end) and how many there are (2 in a 2D deck).
struct NodeSlot
{
  std::uint32_t file;
  std::uint32_t count;
  std::uint64_t begin, end;
};

/// A keyword the mesh does not need (a material, a section, a step's loads), as the deck writes
/// it: the keyword (upper case, without "*"), its parameters (keys upper case, values as written),
/// its data lines and where it stands ("file:line").
struct DeckKeyword
{
  std::string name;
  std::map<std::string, std::string> parameters;
  std::vector<std::string> lines;
  std::string where;
  /// The parameter's value ("" when it has none or is not there).
  std::string get(const std::string& key) const;
  bool has(const std::string& key) const;
};

struct Deck : SourceFile
{
  /// The keywords the mesh does not need, in the deck's order (readDeck only).
  std::vector<DeckKeyword> analysis;
  /// The files read: the deck, then each *INCLUDE as found (paths as opened).
  std::vector<std::string> files;
  /// For each file, its name as the *INCLUDE line wrote it ("" for the deck itself).
  std::vector<std::string> includeNames;
  /// For each file, the hash of its text: a variant is not written from a file changed since.
  std::vector<std::size_t> hashes;
  /// One a node, in mesh.nodeIds' order.
  std::vector<NodeSlot> slots;

  /// The deck and each include read through a relative name (beside target, under that name), with
  /// each node's coordinate fields replaced and every other byte as it was (an unmoved node's line
  /// too). Also refuses a file of the deck changed since it was read, and an include read by its
  /// absolute path that holds nodes. The files are written aside and then renamed.
  void writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
    bool overwrite) const override;
};

/// Reads the deck at path. Throws FileError ("file:line: reason") for what cannot be read: a
/// malformed number, a missing include, a duplicate node id, an element with a missing node, NaN.
/// An element type without a cell type is left out with a warning (mesh.warnings).
Deck readDeck(const std::string& path);

/// Only what writing a variant needs: the files and the nodes' ids, coordinates and slots (no
/// elements or sets), which reads a large deck several times faster than readDeck.
Deck readNodeLayout(const std::string& path);

} // namespace abaqus
} // namespace mlsformats
