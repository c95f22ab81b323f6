// Nastran bulk data (.bdf, .nas, .dat; MSC and NX Nastran's Quick Reference Guide, as Gmsh writes
// it too): the mesh it holds (GRID, the elements, through INCLUDE), and a variant: the deck and its
// included files with only the grids' coordinates changed.
//
// Entries in small field (8 columns), large field (16 columns, "GRID*" with its "*" continuation)
// and free field (commas), each line in its own; continuation lines follow their entry and start
// with "+", "*", "," or a blank; "$" starts a comment; tabs in a fixed-field line stop every 8
// columns. Numbers in Nastran's forms ("1.", ".5", "1.5-3", "-.5+2", "1.E3", "1.D3"). A deck
// with BEGIN BULK or CEND skips its executive and case control statements; ENDDATA ends it;
// INCLUDE 'name' is read relative to the main deck's folder.
//
// A GRID's X1 X2 X3 are in its CP system (CORD2R/C/S, CORD1R/C/S through grids, chains of
// reference systems; a blank CP: GRDSET's, else basic): the mesh holds basic coordinates. The
// elements (QRG's "Element Connection Entries") become VTK cells: CTETRA, CPYRAM, CPENTA, CHEXA
// (without or with all their edge grids), CTRIA3/R, CTRIA6, CQUAD4/R, CQUAD8, CSHEAR, CBAR,
// CBEAM, CROD, CTUBE, CONROD; Nastran takes a solid turned either way, VTK's cell is turned as
// VTK's. Sets: the elements of each property ("PID 7"), the grids of the RBE2s and of the RBE3s
// ("RBE2", "RBE3"), of each SPC1 set ("SPC1 100"). Other elements (CBUSH, CGAP, CWELD...) are
// left out with a warning, their grids read; masses, springs and dampers (CONM2, CELAS1...)
// silently. Refused: part superelements (a second BEGIN), CORD3G and the like as a GRID's system,
// a continuation with no entry before it.
#pragma once

#include "SourceFile.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mlsformats
{
namespace nastran
{
/// A coordinate system resolved into the basic one: a point whose rectangular coordinates in it are
/// (x, y, z) is at origin + x axes[0] + y axes[1] + z axes[2]; its X1 X2 X3 are (x, y, z),
/// (r, theta, z) or (r, theta, phi) with angles in degrees.
struct CoordinateSystem
{
  std::int64_t id = 0;
  char type = 'R'; // 'R' rectangular, 'C' cylindrical, 'S' spherical
  double origin[3] = { 0, 0, 0 };
  double axes[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
};

/// Where a grid is in the deck: the file, where its GRID entry starts, and its CP system.
struct GridSlot
{
  std::uint32_t file;
  std::uint32_t system; // in Deck::systems
  std::uint64_t offset;
};

struct Deck : SourceFile
{
  /// The files read: the deck, then each INCLUDE as found (paths as opened).
  std::vector<std::string> files;
  /// For each file, its name as the INCLUDE wrote it ("" for the deck itself).
  std::vector<std::string> includeNames;
  /// For each file, the hash of its text: a variant is not written from a file changed since.
  std::vector<std::size_t> hashes;
  /// For each file, where the entry of its last grid ends (0: it has none).
  std::vector<std::uint64_t> gridsEnd;
  /// The systems the grids are in, the basic one first.
  std::vector<CoordinateSystem> systems;
  /// One a grid, in mesh.nodeIds' order.
  std::vector<GridSlot> slots;

  /// The deck and each include read through a relative name (beside target, under that name), with
  /// each moved grid's X1 X2 X3 written in its CP system and its field format (small field: 8
  /// characters, "1.2346-5"; large: 16; free: the shortest text), every other byte as it was (an
  /// unmoved grid's entry too; a moved grid's fixed-field line with tabs has them expanded). Also
  /// refuses a file of the deck changed since it was read, and an include read by its absolute path
  /// that holds grids. The files are written aside and renamed.
  void writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
    bool overwrite) const override;
};

/// Reads the deck at path. Throws FileError ("file:line: reason") for what cannot be read: a
/// malformed number, a missing include, a duplicate grid or element id, an element on a missing
/// grid, an undefined or circular coordinate system, NaN. An element without a cell type is left
/// out with a warning (mesh.warnings).
Deck readDeck(const std::string& path);

/// Only what writing a variant needs: the files, the systems and the grids' ids and slots (no
/// coordinates, elements or sets).
Deck readNodeLayout(const std::string& path);

/// Whether text (a file's first bytes) is Nastran input: its first statement is a Nastran one
/// (a word at the line's start) and it has BEGIN BULK, CEND, SOL, a GRID or an element entry (a
/// .dat file may be anything).
bool isNastran(const std::string& head);
} // namespace nastran
} // namespace mlsformats
