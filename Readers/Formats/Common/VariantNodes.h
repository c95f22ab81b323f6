// A variant's nodes matched to its source's: every format's writeVariant starts here.
#pragma once

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
} // namespace mlsformats
