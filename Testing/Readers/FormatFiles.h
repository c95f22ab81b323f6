// What the format and reader tests share: a fresh folder of the test's own, a file written whole,
// the error a read gives, a set by name, and the geometry that checks node orders.
#pragma once

#include "Common/SourceMesh.h"
#include "Common/TextFile.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
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
} // namespace testing
