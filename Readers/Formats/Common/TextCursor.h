// A reader's place in a file's text read whole: the next byte, where the line (or record) read
// last starts, and errors that name the file and that line.
#pragma once

#include "Common/TextFile.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace mlsformats
{
class TextCursor
{
public:
  /// The file at path read whole (FileError when it cannot be).
  explicit TextCursor(const std::string& path);
  virtual ~TextCursor() = default;

protected:
  const std::string Path;
  const std::string Text;
  std::size_t At = 0;   // the next byte to read
  std::size_t Mark = 0; // where the line or record read last starts: errors name it

  /// The line number (from 1) of the byte at offset.
  std::size_t lineOf(std::size_t offset) const;
  /// The error of reason at the byte at offset: naming its line (a binary format names it otherwise).
  virtual FileError errorAt(std::size_t offset, const std::string& reason) const;
  [[noreturn]] void failAt(std::size_t offset, const std::string& reason) const { throw this->errorAt(offset, reason); }
  [[noreturn]] void fail(const std::string& reason) const { this->failAt(this->Mark, reason); }
  /// A count read from the file is at most what the rest of the file holds at bytesEach (at
  /// least) an item: a huge count is refused before anything is allocated for it.
  void room(std::uint64_t count, std::uint64_t bytesEach, const std::string& what) const;
  /// The next line (without "\n" or "\r\n"), its start marked; false at the end of the file.
  bool nextLine(std::string_view& line);
};
} // namespace mlsformats
