#include "Common/TextFile.h"

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fcntl.h>
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

std::string readHead(const std::string& path, std::size_t bytes)
{
  std::ifstream in(path, std::ios::binary);
  std::string head(bytes, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head;
}

namespace
{
// contentHash's chunks: hashed side by side, then their hashes hashed
constexpr std::size_t HashChunk = std::size_t(1) << 22;

std::size_t hashOfChunks(const std::vector<std::size_t>& chunks)
{
  return std::hash<std::string_view>()(std::string_view(reinterpret_cast<const char*>(chunks.data()), chunks.size() * sizeof(std::size_t)));
}

// The regular file at path opened to read, and its size. Throws FileError.
Descriptor openToRead(const std::string& path, std::size_t& size)
{
  Descriptor file(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  struct stat status;
  if (file.get() < 0 || ::fstat(file.get(), &status) != 0 || !S_ISREG(status.st_mode))
  {
    throw FileError(path, 0, "cannot be read (no such file, or no permission)");
  }
  size = static_cast<std::size_t>(status.st_size);
  return file;
}

// Reads [at, at + length) of file into data; false when the file ends first or a read fails.
bool readAt(int file, char* data, std::size_t length, std::size_t at)
{
  while (length > 0)
  {
    const ssize_t read = ::pread(file, data, length, static_cast<off_t>(at));
    if (read < 0 && errno == EINTR)
    {
      continue;
    }
    if (read <= 0)
    {
      return false;
    }
    data += read;
    at += static_cast<std::size_t>(read);
    length -= static_cast<std::size_t>(read);
  }
  return true;
}
} // namespace

std::size_t contentHash(std::string_view bytes)
{
  std::vector<std::size_t> chunks((bytes.size() + HashChunk - 1) / HashChunk);
#pragma omp parallel for schedule(dynamic)
  for (long c = 0; c < static_cast<long>(chunks.size()); ++c)
  {
    chunks[c] = std::hash<std::string_view>()(bytes.substr(c * HashChunk, HashChunk));
  }
  return hashOfChunks(chunks);
}

bool Descriptor::close()
{
  const int descriptor = this->Value;
  this->Value = -1;
  return descriptor < 0 || ::close(descriptor) == 0;
}

SourceBytes::SourceBytes(const std::string& path, std::size_t hash, const char* noun)
  : Path(path)
  , Noun(noun)
  , Expected(hash)
{
  this->File = openToRead(path, this->Size);
}

void SourceBytes::readInto(char* data, std::size_t begin, std::size_t end)
{
  if (begin != this->Next || end < begin)
  {
    throw std::logic_error("SourceBytes: bytes [" + std::to_string(begin) + ", " + std::to_string(end) + ") are not the next of " +
      this->Path + " (at " + std::to_string(this->Next) + " of " + std::to_string(this->Size) + ")");
  }
  if (end > this->Size || !readAt(this->File.get(), data, end - begin, begin))
  {
    throw FileError(this->Path, 0, "has changed since it was read (it is shorter): read the " + std::string(this->Noun) + " again");
  }
  this->pass(std::string_view(data, end - begin));
}

void SourceBytes::pass(std::string_view bytes)
{
  this->Next += bytes.size();
  while (!bytes.empty())
  {
    if (this->Partial.empty() && bytes.size() >= HashChunk)
    {
      this->Chunks.push_back(std::hash<std::string_view>()(bytes.substr(0, HashChunk)));
      bytes.remove_prefix(HashChunk);
      continue;
    }
    const std::size_t taken = std::min(HashChunk - this->Partial.size(), bytes.size());
    this->Partial.append(bytes.substr(0, taken));
    bytes.remove_prefix(taken);
    if (this->Partial.size() == HashChunk)
    {
      this->Chunks.push_back(std::hash<std::string_view>()(this->Partial));
      this->Partial.clear();
    }
  }
  if (this->Next == this->Size)
  {
    if (!this->Partial.empty())
    {
      this->Chunks.push_back(std::hash<std::string_view>()(this->Partial));
      this->Partial.clear();
    }
    if (hashOfChunks(this->Chunks) != this->Expected)
    {
      throw FileError(this->Path, 0, "has changed since it was read: read the " + std::string(this->Noun) + " again");
    }
  }
}

std::string_view SourceBytes::read(std::size_t begin, std::size_t end)
{
  this->Bytes.resize(end - begin);
  this->readInto(this->Bytes.data(), begin, end);
  return this->Bytes;
}

std::size_t fileHash(const std::string& path)
{
  std::size_t size = 0;
  Descriptor file = openToRead(path, size);
  std::vector<std::size_t> chunks((size + HashChunk - 1) / HashChunk);
  bool whole = true;
#pragma omp parallel
  {
    std::string chunk(HashChunk, '\0'); // this thread's
#pragma omp for schedule(dynamic) reduction(&& : whole)
    for (long c = 0; c < static_cast<long>(chunks.size()); ++c)
    {
      const std::size_t at = c * HashChunk, length = std::min(HashChunk, size - at);
      whole = readAt(file.get(), chunk.data(), length, at) && whole;
      chunks[c] = std::hash<std::string_view>()(std::string_view(chunk.data(), length));
    }
  }
  if (!whole)
  {
    throw FileError(path, 0, "a read failed (or the file changed while it was read)");
  }
  return hashOfChunks(chunks);
}

AtomicWrite::AtomicWrite(bool overwrite)
  : Overwrite(overwrite)
{
}

AtomicWrite::~AtomicWrite()
{
  std::error_code ignored;
  for (const auto& [aside, path] : this->Pending)
  {
    std::filesystem::remove(aside, ignored);
  }
  // the folders made for what is not committed, a folder's after those in it (longer paths)
  std::sort(this->Made.begin(), this->Made.end(), [](const std::string& a, const std::string& b) { return a.size() > b.size(); });
  for (const std::string& folder : this->Made)
  {
    std::filesystem::remove(folder, ignored); // only when empty
  }
}

void AtomicWrite::Aside::append(std::string_view bytes)
{
  while (!bytes.empty() && this->Failure.empty())
  {
    const ssize_t written = ::write(this->File.get(), bytes.data(), bytes.size());
    if (written < 0 && errno == EINTR)
    {
      continue;
    }
    if (written <= 0)
    {
      this->Failure = written < 0 ? std::strerror(errno) : "no space";
      return;
    }
    bytes.remove_prefix(static_cast<std::size_t>(written));
  }
}

void AtomicWrite::Aside::copy(SourceBytes& source, std::size_t begin, std::size_t end)
{
  // in chunks of the hash's size, at its chunks' bounds: each read is hashed whole
  source.Buffer.resize(std::min(end - begin, HashChunk));
  for (std::size_t at = begin; at < end;)
  {
    const std::size_t next = std::min(end, (at / HashChunk + 1) * HashChunk);
    source.readInto(source.Buffer.data(), at, next);
    this->append(std::string_view(source.Buffer.data(), next - at));
    at = next;
  }
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
  for (std::filesystem::path missing = folder; !missing.empty() && !std::filesystem::exists(missing); missing = missing.parent_path())
  {
    this->Made.push_back(missing.string());
  }
  if (!folder.empty())
  {
    std::filesystem::create_directories(folder, made);
  }
  this->Pending.emplace_back(aside.Written, path);
  aside.File = Descriptor(::open(aside.Written.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666));
  if (aside.File.get() < 0)
  {
    throw FileError(path, 0, "cannot be written (" + (made ? made.message() : std::string(std::strerror(errno))) + ")");
  }
  return aside;
}

std::string AtomicWrite::close(Aside& aside)
{
  if (!aside.File.close() && aside.Failure.empty())
  {
    aside.Failure = std::strerror(errno);
  }
  if (!aside.Failure.empty())
  {
    throw FileError(aside.Path, 0, "cannot be written (" + aside.Failure + ")");
  }
  return aside.Written;
}

std::string AtomicWrite::add(const std::string& path, std::string_view bytes)
{
  Aside aside = this->open(path);
  aside.append(bytes);
  return this->close(aside);
}

std::string AtomicWrite::add(const std::string& path, SourceBytes& source)
{
  Aside aside = this->open(path);
  aside.copy(source, 0, source.size());
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
  this->Made.clear();
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

std::size_t appendNumbers(std::string& out, std::string_view text, std::size_t begin, int count, const double* xyz, const double* old)
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
    double value = 0;
    if (old ? old[c] == xyz[c] : parseReal(text.data() + begin, text.data() + end, value) && value == xyz[c])
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
