#include "Common/VariantNodes.h"

#include "Common/IdIndex.h"
#include "Common/TextFile.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace mlsformats
{
std::vector<std::size_t> variantRows(const std::string& target, const std::string& source,
  const std::vector<std::int64_t>& nodeIds, const std::int64_t* ids, const double* xyz, std::size_t count)
{
  if (count != nodeIds.size())
  {
    throw FileError(target, 0, "the data has " + std::to_string(count) + " points; " + source + " has " +
        std::to_string(nodeIds.size()) + " nodes (is it that file's mesh?)");
  }
  std::vector<std::size_t> row(count);
  if (std::equal(nodeIds.begin(), nodeIds.end(), ids))
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      row[i] = i;
    }
  }
  else
  {
    const IdIndex index(nodeIds);
    std::vector<char> seen(count, 0);
    for (std::size_t i = 0; i < count; ++i)
    {
      const std::size_t at = index.find(ids[i]);
      if (at == IdIndex::none || seen[at])
      {
        throw FileError(target, 0, "node " + std::to_string(ids[i]) + (at == IdIndex::none ? " is not in " : " comes twice, once in ") +
            source + " (is the data that file's mesh?)");
      }
      seen[at] = 1;
      row[at] = i;
    }
  }
  for (std::size_t i = 0; i < 3 * count; ++i)
  {
    if (!std::isfinite(xyz[i]))
    {
      throw FileError(target, 0, "node " + std::to_string(ids[i / 3]) + " has a coordinate that is not finite");
    }
  }
  return row;
}

std::vector<std::string> variantDestinations(const std::string& target, const std::vector<std::string>& files,
  const std::vector<std::string>& includeNames, const std::vector<char>& holdsNodes)
{
  const std::filesystem::path folder = std::filesystem::path(target).parent_path();
  std::vector<std::string> destinations(files.size()), sources;
  for (const std::string& file : files)
  {
    sources.push_back(canonicalPath(file));
  }
  for (std::size_t f = 0; f < files.size(); ++f)
  {
    const std::string& name = includeNames[f];
    if (f > 0 && std::filesystem::path(name).is_absolute())
    {
      if (holdsNodes[f])
      {
        throw FileError(files[f], 0, "holds nodes and is included by its absolute path: a variant cannot be written beside " +
            target + " under that name (include it by a relative name)");
      }
      continue; // read where it is, by the variant as by the source
    }
    destinations[f] = f == 0 ? target : (folder / name).string();
    if (std::find(sources.begin(), sources.end(), canonicalPath(destinations[f])) != sources.end())
    {
      throw FileError(destinations[f], 0, "is a file of the source " + files[0] + ": a variant is written elsewhere");
    }
  }
  return destinations;
}

VariantSource variantSource(const std::string& target, const std::string& source, std::size_t hash,
  const std::vector<std::int64_t>& nodeIds, const std::int64_t* ids, const double* xyz, std::size_t count)
{
  std::vector<std::size_t> row = variantRows(target, source, nodeIds, ids, xyz, count);
  if (canonicalPath(target) == canonicalPath(source))
  {
    throw FileError(target, 0, "is the source mesh: a variant is written elsewhere");
  }
  return VariantSource{ std::move(row), SourceBytes(source, hash) };
}
} // namespace mlsformats
