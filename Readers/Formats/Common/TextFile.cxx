#include "Common/TextFile.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace mlsformats
{
namespace
{
std::string where(const std::string& file, std::size_t line)
{
  return line > 0 ? file + ":" + std::to_string(line) : file;
}
}

FileError::FileError(const std::string& file_, std::size_t line_, const std::string& reason)
  : std::runtime_error(where(file_, line_) + ": " + reason)
  , file(file_)
  , line(line_)
{
}

std::string canonicalPath(const std::string& path)
{
  std::error_code ignored;
  return std::filesystem::weakly_canonical(path, ignored).string();
}

std::string readFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
  {
    throw FileError(path, 0, "cannot be read (no such file, or no permission)");
  }
  // read at once into a string of the file's size (a string stream would copy it as it grows)
  const std::streamoff size = in.tellg();
  std::string text(size > 0 ? static_cast<std::size_t>(size) : 0, '\0');
  in.seekg(0);
  if (size < 0 || !in.read(text.data(), size) || in.peek() != std::char_traits<char>::eof())
  {
    throw FileError(path, 0, "a read failed (or the file changed while it was read)");
  }
  return text;
}

MappedFile::MappedFile(const std::string& path)
{
  const int file = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat status;
  if (file < 0 || ::fstat(file, &status) != 0 || !S_ISREG(status.st_mode))
  {
    if (file >= 0)
    {
      ::close(file);
    }
    throw FileError(path, 0, "cannot be read (no such file, or no permission)");
  }
  this->Size = static_cast<std::size_t>(status.st_size);
  if (this->Size > 0)
  {
    void* data = ::mmap(nullptr, this->Size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, file, 0);
    if (data == MAP_FAILED)
    {
      ::close(file);
      throw FileError(path, 0, "cannot be mapped into memory to be read");
    }
    this->Data = static_cast<const char*>(data);
  }
  ::close(file); // the mapping keeps the file
}

MappedFile::MappedFile(MappedFile&& other) noexcept
  : Data(other.Data)
  , Size(other.Size)
{
  other.Data = nullptr;
  other.Size = 0;
}

MappedFile::~MappedFile()
{
  if (this->Data)
  {
    ::munmap(const_cast<char*>(this->Data), this->Size);
  }
}

std::size_t contentHash(std::string_view bytes)
{
  // the hashes of 4 MiB chunks taken side by side, then hashed: the same for any number of threads
  constexpr std::size_t Chunk = std::size_t(1) << 22;
  std::vector<std::size_t> chunks((bytes.size() + Chunk - 1) / Chunk);
#pragma omp parallel for schedule(dynamic)
  for (long c = 0; c < static_cast<long>(chunks.size()); ++c)
  {
    chunks[c] = std::hash<std::string_view>()(bytes.substr(c * Chunk, Chunk));
  }
  return std::hash<std::string_view>()(std::string_view(reinterpret_cast<const char*>(chunks.data()), chunks.size() * sizeof(std::size_t)));
}

AtomicWrite::AtomicWrite(bool overwrite)
  : Overwrite(overwrite)
{
}

AtomicWrite::~AtomicWrite()
{
  for (const auto& [aside, path] : this->Pending)
  {
    std::error_code ignored;
    std::filesystem::remove(aside, ignored);
  }
}

void AtomicWrite::Aside::append(std::string_view bytes)
{
  this->Out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

AtomicWrite::Aside AtomicWrite::open(const std::string& path)
{
  if (!this->Overwrite && std::filesystem::exists(path))
  {
    throw FileError(path, 0, "exists already (overwrite it or choose another name)");
  }
  Aside aside;
  aside.Path = path;
  aside.Written = path + ".writing-" + std::to_string(::getpid());
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code made;
  if (!folder.empty())
  {
    std::filesystem::create_directories(folder, made);
  }
  aside.Unmade = made ? made.message() : std::string();
  this->Pending.emplace_back(aside.Written, path);
  aside.Out.open(aside.Written, std::ios::binary | std::ios::trunc);
  return aside;
}

std::string AtomicWrite::close(Aside& aside)
{
  aside.Out.close();
  if (!aside.Out)
  {
    throw FileError(aside.Path, 0, "cannot be written (" + (aside.Unmade.empty() ? std::string("no space or no permission") : aside.Unmade) + ")");
  }
  return aside.Written;
}

std::string AtomicWrite::add(const std::string& path, std::string_view bytes)
{
  Aside aside = this->open(path);
  aside.append(bytes);
  return this->close(aside);
}

void AtomicWrite::commit()
{
  // the last added first: the first (a deck, which names the others) appears when all are in place
  for (auto pending = this->Pending.rbegin(); pending != this->Pending.rend(); ++pending)
  {
    const auto& [aside, path] = *pending;
    std::error_code failed;
    std::filesystem::rename(aside, path, failed);
    if (failed)
    {
      throw FileError(path, 0, "cannot be renamed into place: " + failed.message());
    }
  }
  this->Pending.clear();
}

bool parseInteger(const char* first, const char* last, std::int64_t& value)
{
  if (first < last && *first == '+')
  {
    ++first;
  }
  const auto [end, error] = std::from_chars(first, last, value);
  return first < last && error == std::errc() && end == last;
}

bool parseReal(const char* first, const char* last, double& value)
{
  if (first < last && *first == '+')
  {
    ++first;
  }
  auto [end, error] = std::from_chars(first, last, value);
  if (error == std::errc() && end < last && (*end == 'D' || *end == 'd') && last - first < 64)
  {
    char copy[64];
    std::copy(first, last, copy);
    copy[end - first] = 'E';
    const auto parsed = std::from_chars(copy, copy + (last - first), value);
    end = first + (parsed.ptr - copy);
    error = parsed.ec;
  }
  return first < last && error == std::errc() && end == last && std::isfinite(value);
}

void appendShortest(std::string& out, double value, std::size_t width)
{
  char text[32];
  auto written = std::to_chars(text, text + sizeof(text), value);
  // too wide: the most significant digits that fit (%g's choice of fixed or exponent)
  for (int digits = 16; static_cast<std::size_t>(written.ptr - text) > width && digits > 0; --digits)
  {
    written = std::to_chars(text, text + sizeof(text), value, std::chars_format::general, digits);
  }
  out.append(text, written.ptr);
}

std::string_view trim(std::string_view text)
{
  while (!text.empty() && isBlank(text.front()))
  {
    text.remove_prefix(1);
  }
  while (!text.empty() && isBlank(text.back()))
  {
    text.remove_suffix(1);
  }
  return text;
}

void splitBlanks(std::string_view text, std::vector<std::string_view>& fields)
{
  fields.clear();
  std::size_t begin = 0;
  while (true)
  {
    while (begin < text.size() && isBlank(text[begin]))
    {
      ++begin;
    }
    if (begin == text.size())
    {
      return;
    }
    std::size_t end = begin;
    while (end < text.size() && !isBlank(text[end]))
    {
      ++end;
    }
    fields.push_back(text.substr(begin, end - begin));
    begin = end;
  }
}

std::size_t appendNumbers(std::string& out, std::string_view text, std::size_t begin, int count, const double* xyz)
{
  std::size_t end = begin;
  for (int c = 0; c < count; ++c)
  {
    const std::size_t blanks = end;
    while (begin < text.size() && (isBlank(text[begin]) || text[begin] == '\r' || text[begin] == '\n'))
    {
      ++begin;
    }
    out.append(text, blanks, begin - blanks);
    end = begin;
    while (end < text.size() && !isBlank(text[end]) && text[end] != '\r' && text[end] != '\n' && text[end] != '(' &&
      text[end] != ')')
    {
      ++end;
    }
    double old = 0;
    if (parseReal(text.data() + begin, text.data() + end, old) && old == xyz[c])
    {
      out.append(text, begin, end - begin);
    }
    else
    {
      appendShortest(out, xyz[c]);
    }
    begin = end;
  }
  return end;
}

bool nextLine(std::string_view text, std::size_t& at, std::string_view& line)
{
  if (at >= text.size())
  {
    return false;
  }
  std::size_t end = text.find('\n', at);
  const std::size_t next = end == std::string::npos ? text.size() : end + 1;
  end = end == std::string::npos ? text.size() : end;
  line = text.substr(at, end - at);
  if (!line.empty() && line.back() == '\r')
  {
    line.remove_suffix(1);
  }
  at = next;
  return true;
}

std::vector<Line> lines(std::string_view text)
{
  std::vector<Line> out;
  std::size_t begin = 0;
  while (begin < text.size())
  {
    std::size_t end = text.find('\n', begin);
    const std::size_t next = end == std::string::npos ? text.size() : end + 1;
    end = end == std::string::npos ? text.size() : end;
    const std::size_t content = end > begin && text[end - 1] == '\r' ? end - 1 : end;
    out.push_back({ begin, content, next });
    begin = next;
  }
  return out;
}
} // namespace mlsformats
