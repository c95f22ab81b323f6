// What the format and reader tests share: a fresh folder of the test's own, a file written whole,
// the error a read gives, a set by name.
#pragma once

#include "Common/SourceMesh.h"
#include "Common/TextFile.h"

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
} // namespace testing
