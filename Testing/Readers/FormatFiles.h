// What the format and reader tests share: a fresh folder of the test's own, a file written whole,
// the error a read or a variant gives, a set by name, meshes compared, the geometry that checks
// node orders, and the refusals every format's variant writer makes.
#pragma once

#include "../TestHarness.h"
#include "Common/SourceMesh.h"
#include "Common/TextFile.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace testing
{
/// TEST_OUTPUT_DIR/group/name, emptied: a folder of each test's own (ctest -j runs them side by side).
inline std::string freshFolder(const std::string& group, const std::string& name)
{
  const std::filesystem::path path = std::filesystem::path(TEST_OUTPUT_DIR) / group / name;
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
  return path.string();
}

/// folder(name): freshFolder(group, name), a format test's folder (const TestFolders folder{ "gmsh" };).
struct TestFolders
{
  std::string group;
  std::string operator()(const std::string& name) const { return freshFolder(group, name); }
};

/// Writes text to path (its folder made) and returns path.
inline std::string writeFile(const std::string& path, const std::string& text)
{
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

inline bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

/// Whether variant is source with some of its bytes, and at most bytes of them, changed (the
/// same size): a binary variant rewrites only its moved coordinates' bytes.
inline bool changedAtMost(const std::string& source, const std::string& variant, std::size_t bytes)
{
  std::size_t differing = 0;
  for (std::size_t b = 0; b < source.size() && b < variant.size(); ++b)
  {
    differing += source[b] != variant[b] ? 1 : 0;
  }
  std::printf("%zu of %zu bytes differ\n", differing, source.size());
  return variant.size() == source.size() && differing > 0 && differing <= bytes;
}

/// The set of that name, or nullptr.
inline const mlsformats::NamedSet* find(const std::vector<mlsformats::NamedSet>& sets, const std::string& name)
{
  for (const mlsformats::NamedSet& set : sets)
  {
    if (set.name == name)
    {
      return &set;
    }
  }
  return nullptr;
}

/// The message of the FileError that read() throws, printed; "" when it reads.
template <class Read>
std::string readError(Read read)
{
  try
  {
    read();
  }
  catch (const mlsformats::FileError& e)
  {
    std::printf("expected error: %s\n", e.what());
    return e.what();
  }
  return "";
}

/// readError(path): the message of the FileError that read(path) throws, printed; "" when it reads
/// (const ReadErrors readError{ gmsh::readMsh };).
template <class Read>
struct ReadErrors
{
  Read read;
  std::string operator()(const std::string& path) const
  {
    return testing::readError([&] { read(path); });
  }
};
template <class Read>
ReadErrors(Read) -> ReadErrors<Read>;

/// The message of the FileError that writing file's variant at target throws (ids.size() nodes),
/// printed; "" when it is written.
template <class File>
std::string writeError(const File& file, const std::string& target, const std::vector<std::int64_t>& ids,
  const std::vector<double>& xyz, bool overwrite = false)
{
  return testing::readError([&] { file.writeVariant(target, ids.data(), xyz.data(), ids.size(), overwrite); });
}

inline bool sameSets(const std::vector<mlsformats::NamedSet>& a, const std::vector<mlsformats::NamedSet>& b)
{
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
    [](const mlsformats::NamedSet& x, const mlsformats::NamedSet& y) { return x.name == y.name && x.ids == y.ids; });
}

/// Whether the meshes are the same but for their coordinates and warnings.
inline bool sameTopology(const mlsformats::SourceMesh& a, const mlsformats::SourceMesh& b)
{
  return a.nodeIds == b.nodeIds && sameSets(a.nodeSets, b.nodeSets) && sameSets(a.elementSets, b.elementSets) &&
    std::equal(a.blocks.begin(), a.blocks.end(), b.blocks.begin(), b.blocks.end(),
      [](const mlsformats::ElementBlock& x, const mlsformats::ElementBlock& y) {
        return x.name == y.name && x.type == y.type && x.ids == y.ids && x.nodes == y.nodes;
      });
}

/// Whether the meshes are the same but for their warnings.
inline bool sameMesh(const mlsformats::SourceMesh& a, const mlsformats::SourceMesh& b)
{
  return a.xyz == b.xyz && sameTopology(a, b);
}

using Point = std::array<double, 3>;

/// The position of node id in mesh.
inline Point position(const mlsformats::SourceMesh& mesh, std::int64_t id)
{
  const std::size_t at = static_cast<std::size_t>(std::find(mesh.nodeIds.begin(), mesh.nodeIds.end(), id) - mesh.nodeIds.begin());
  return { mesh.xyz[3 * at], mesh.xyz[3 * at + 1], mesh.xyz[3 * at + 2] };
}

/// (p1 - p0) x (p2 - p0) . (p3 - p0): a corner's orientation.
inline double tripleProduct(const Point& p0, const Point& p1, const Point& p2, const Point& p3)
{
  const Point a{ p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] }, b{ p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] },
    c{ p3[0] - p0[0], p3[1] - p0[1], p3[2] - p0[2] };
  return (a[1] * b[2] - a[2] * b[1]) * c[0] + (a[2] * b[0] - a[0] * b[2]) * c[1] + (a[0] * b[1] - a[1] * b[0]) * c[2];
}

/// Whether the node corners + i of every cell of block is at the middle of its VTK edge edges[i].
inline bool midsideNodesOnTheirEdges(
  const mlsformats::SourceMesh& mesh, const mlsformats::ElementBlock& block, int corners, const std::vector<std::array<int, 2>>& edges)
{
  const int perCell = mlsformats::nodesPerCell(block.type);
  for (std::size_t e = 0; e < block.ids.size(); ++e)
  {
    const std::int64_t* nodes = block.nodes.data() + e * perCell;
    for (std::size_t i = 0; i < edges.size(); ++i)
    {
      const Point a = position(mesh, nodes[edges[i][0]]), b = position(mesh, nodes[edges[i][1]]);
      const Point middle = position(mesh, nodes[corners + i]);
      for (int c = 0; c < 3; ++c)
      {
        if (middle[c] != (a[c] + b[c]) / 2)
        {
          std::printf("%s: node %zu is not on the edge %d-%d\n", block.name.c_str(), corners + i, edges[i][0], edges[i][1]);
          return false;
        }
      }
    }
  }
  return true;
}

/// Whether the files at a and b hold the same bytes.
inline bool sameBytes(const std::string& a, const std::string& b)
{
  return mlsformats::readFile(a) == mlsformats::readFile(b);
}

/// Whether no file or folder in dir, or below it, is one written aside (".writing-"): nothing is
/// left half-written.
inline bool nothingWrittenAside(const std::string& dir)
{
  bool none = true;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
  {
    if (entry.path().string().find(".writing-") != std::string::npos)
    {
      std::printf("left aside: %s\n", entry.path().string().c_str());
      none = false;
    }
  }
  return none;
}

/// Whether File is a deck (a main file and its includes: abaqus::Deck, nastran::Deck), whose
/// variant writer words two refusals its own way.
template <class File, class = void>
struct IsDeck : std::false_type
{
};
template <class File>
struct IsDeck<File, std::void_t<decltype(std::declval<const File&>().files)>> : std::true_type
{
};

/// The refusals every format's variant writer makes, each a FileError that names the target (or
/// the file to blame) and why, with nothing written at the target; file is source read (a mesh of
/// two nodes or more), the variants go to dir/v/ and dir/c/ under the source's name:
/// - data of another node count, a node id not in the source, a node twice, a coordinate not finite;
/// - the source itself as the target, by its name and by another spelling of it (the source stays);
/// - a target that exists, unless overwrite is set: then the variant of the unchanged nodes is the
///   source, as same(target, source) compares them (byte for byte unless the format says otherwise);
/// - a source changed since it was read: edit appended to edited (the file that holds the nodes:
///   "" for source, else the deck's include), its last byte changed, or cut to half its size;
/// and no file left aside (".writing-") anywhere in dir.
template <class File, class Same = bool (*)(const std::string&, const std::string&)>
void checkVariantRefusals(const File& file, const std::string& source, const std::string& dir, const std::string& edit,
  const std::string& edited = "", Same same = sameBytes)
{
  namespace fs = std::filesystem;
  const bool deck = IsDeck<File>::value;
  const std::vector<std::int64_t>& ids = file.mesh.nodeIds;
  const std::vector<double>& xyz = file.mesh.xyz;
  const std::size_t count = ids.size();
  const std::string name = fs::path(source).filename().string();
  const std::string target = dir + "/v/" + name;
  std::printf("the refusals of a variant of %s\n", source.c_str());
  // another node count, another node id, a node twice, a coordinate not finite
  CHECK(contains(writeError(file, target, std::vector<std::int64_t>(ids.begin(), ids.end() - 1), xyz),
    target + ": the data has " + std::to_string(count - 1) + " points; " + source + " has " + std::to_string(count) + " nodes"));
  std::vector<std::int64_t> other = ids;
  const std::size_t k = std::min<std::size_t>(3, count - 1);
  other[k] = *std::max_element(ids.begin(), ids.end()) + 1;
  CHECK(contains(writeError(file, target, other, xyz), target + ": node " + std::to_string(other[k]) + " is not in " + source));
  other[k] = ids[0];
  CHECK(contains(writeError(file, target, other, xyz), target + ": node " + std::to_string(ids[0]) + " comes twice, once in " + source));
  std::vector<double> nan = xyz;
  nan[4] = std::numeric_limits<double>::quiet_NaN();
  CHECK(contains(writeError(file, target, ids, nan), target + ": node " + std::to_string(ids[1]) + " has a coordinate that is not finite"));
  // onto the source, by its name or another spelling of it, even with overwrite set
  const std::string before = mlsformats::readFile(source);
  for (const std::string& itself : { source, (fs::path(source).parent_path() / "." / name).string() })
  {
    CHECK(contains(writeError(file, itself, ids, xyz, true),
      itself + (deck ? ": is a file of the source " + source : std::string(": is the source mesh")) + ": a variant is written elsewhere"));
  }
  CHECK(mlsformats::readFile(source) == before);
  CHECK(!fs::exists(target));
  // an existing variant (written here, a deck's includes with it) stays unless overwrite is set
  CHECK(writeError(file, target, ids, xyz).empty());
  writeFile(target, "kept");
  CHECK(contains(writeError(file, target, ids, xyz), target + ": exists already"));
  CHECK(mlsformats::readFile(target) == "kept");
  CHECK(writeError(file, target, ids, xyz, true).empty());
  CHECK(same(target, source));
  // a source changed since it was read: edited, a byte that is copied (not parsed) changed in
  // place, cut short (which a mapped source would have answered with SIGBUS)
  const std::string changed = edited.empty() ? source : edited;
  const std::string original = mlsformats::readFile(changed);
  std::string lastByte = original;
  lastByte.back() = lastByte.back() == 'x' ? 'y' : 'x';
  const std::string later = dir + "/c/" + name;
  const std::string again = std::string(": read the ") + (deck ? "deck" : "mesh") + " again";
  writeFile(changed, original + edit);
  CHECK(contains(writeError(file, later, ids, xyz), changed + ": has changed since it was read" + again));
  for (const std::string& text : { lastByte, original.substr(0, original.size() / 2) })
  {
    writeFile(changed, text);
    const std::string error = writeError(file, later, ids, xyz);
    CHECK(contains(error, changed + ": has changed since it was read") && contains(error, again));
  }
  writeFile(changed, original);
  CHECK(!fs::exists(later) && !fs::exists(dir + "/c"));
  CHECK(nothingWrittenAside(dir));
}
} // namespace testing
