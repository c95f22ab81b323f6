// The formats of the solvers' mesh files, one table: how a file of each is recognized and read,
// and how a variant of it is written. A new format adds a folder and a row (SourceFile.cxx).
#pragma once

#include "Common/SourceMesh.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mlsformats
{
/// A mesh file as read: its mesh, and the writing of its variants.
class SourceFile
{
public:
  virtual ~SourceFile() = default;
  /// The mesh (read as a layout: its node ids, and its coordinates where a variant compares them).
  SourceMesh mesh;
  /// Writes the variant whose node ids[i] is at xyz[3i..3i+2] to target: the source with only the
  /// node coordinates changed. Throws FileError, having written nothing, when ids are not the
  /// source's node ids (in any order), when target is one of the source's files, or exists and
  /// overwrite is not set.
  virtual void writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
    bool overwrite) const = 0;
};

struct Format
{
  const char* name;       // "Abaqus/CalculiX deck"
  const char* extensions; // "inp", several separated by blanks
  /// Whose mesh-quality verdict its meshes get: an FEM solver's (true: the elements' Jacobian) or
  /// a finite-volume solver's (false: checkMesh's face measures).
  bool fem;
  /// Whether text (a file's first bytes) is of this format.
  bool (*recognizes)(const std::string& text);
  /// The file read whole, or (layout) only what writing a variant needs.
  std::unique_ptr<SourceFile> (*read)(const std::string& path, bool layout);
};

/// Every format.
const std::vector<Format>& formats();

/// The format of the file at path, by its extension and its first bytes; nullptr if none.
const Format* formatOf(const std::string& path);
} // namespace mlsformats
