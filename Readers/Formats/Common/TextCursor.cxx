#include "Common/TextCursor.h"

#include <algorithm>

namespace mlsformats
{
TextCursor::TextCursor(const std::string& path)
  : Path(path)
  , Text(readFile(path))
{
}

std::size_t TextCursor::lineOf(std::size_t offset) const
{
  offset = std::min(offset, this->Text.empty() ? 0 : this->Text.size() - 1);
  return 1 + static_cast<std::size_t>(std::count(this->Text.begin(), this->Text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

FileError TextCursor::errorAt(std::size_t offset, const std::string& reason) const
{
  return FileError(this->Path, this->lineOf(offset), reason);
}

void TextCursor::room(std::uint64_t count, std::uint64_t bytesEach, const std::string& what) const
{
  if (count > (this->Text.size() - this->At) / bytesEach)
  {
    this->fail(std::to_string(count) + " " + what + ": more than the rest of the file holds (is it cut short?)");
  }
}

bool TextCursor::nextLine(std::string_view& line)
{
  const std::size_t at = this->At;
  if (!mlsformats::nextLine(this->Text, this->At, line))
  {
    return false;
  }
  this->Mark = at;
  return true;
}
} // namespace mlsformats
