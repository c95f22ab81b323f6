// A variant's nodes matched to its source's: every format's writeVariant starts here.
#pragma once

#include "Common/TextFile.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mlsformats
{
/// For each of the source's nodes (nodeIds, in its order), where it is among the variant's:
/// ids[row[k]] == nodeIds[k], its coordinates at xyz[3 row[k] ..]. Throws FileError naming target
/// and source when the variant is not of that mesh (another count, an id missing or twice) or a
/// coordinate is not finite.
std::vector<std::size_t> variantRows(const std::string& target, const std::string& source,
  const std::vector<std::int64_t>& nodeIds, const std::int64_t* ids, const double* xyz, std::size_t count);
/// What a one-file format's variant starts from: where each source node is among the variant's
/// (variantRows) and the source file, its hash checked as it is read (SourceBytes). Throws FileError, besides variantRows' refusals, when
/// target is the source file (by any spelling of its path) and when the source's bytes are not
/// those read (their hash): a variant is written from the file as it was read, or not at all.
struct VariantSource
{
  std::vector<std::size_t> row;
  SourceBytes file;
};
VariantSource variantSource(const std::string& target, const std::string& source, std::size_t hash,
  const std::vector<std::int64_t>& nodeIds, const std::int64_t* ids, const double* xyz, std::size_t count);

/// Where the files of a variant of a source made of several files go (files[0] the main file, the
/// others included under includeNames): the main file at target, each file included by a relative
/// name beside it under that name, and "" (not written: the variant reads it where it is) for one
/// included by its absolute path. Throws FileError for such a file that holds nodes (holdsNodes),
/// and for a destination that is one of the source's files.
std::vector<std::string> variantDestinations(const std::string& target, const std::vector<std::string>& files,
  const std::vector<std::string>& includeNames, const std::vector<char>& holdsNodes);
} // namespace mlsformats
