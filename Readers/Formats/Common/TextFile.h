// What every format's reading and writing shares: an error that names the file and the line,
// a whole file read at once, a file written aside and renamed into place (never half-written),
// and the shortest text of a double that reads back as the same double.
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mlsformats
{
/// An error in a file, "file:line: reason" (line 0: the file as a whole).
class FileError : public std::runtime_error
{
public:
  FileError(const std::string& file, std::size_t line, const std::string& reason);
  std::string file;
  std::size_t line;
};

/// The path with its folders resolved as far as they exist (symbolic links, "..", "."): two paths
/// of the same file compare equal.
std::string canonicalPath(const std::string& path);

/// The whole file. Throws FileError when it cannot be read.
std::string readFile(const std::string& path);

/// The whole file mapped into memory read-only: its bytes are the page cache's own, neither copied
/// nor zeroed first, so a variant's unchanged bytes go from the source's pages straight to the
/// variant's (AtomicWrite::add). Throws FileError when it cannot be read. The file must not be
/// truncated while it is mapped (the bytes past its new end would be gone): a variant is written
/// within a second of mapping its source, and a source replaced by a new file (renamed over it, as
/// editors and solvers save) keeps its mapped bytes.
class MappedFile
{
public:
  explicit MappedFile(const std::string& path);
  MappedFile(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  MappedFile& operator=(MappedFile&&) = delete;
  ~MappedFile();
  std::string_view bytes() const { return std::string_view(this->Data, this->Size); }

private:
  const char* Data = nullptr;
  std::size_t Size = 0;
};

/// The hash of a file's bytes, taken when it is read and checked before a variant is written from
/// it (a variant is written from the bytes that were read, or not at all).
std::size_t contentHash(std::string_view bytes);

/// The files written into place at once: each is written aside (path.writing-<process>), and only
/// once all are written are they renamed into place; a failure removes what was written aside and
/// throws FileError. Existing files are replaced only when overwrite is set (else FileError).
class AtomicWrite
{
public:
  /// A file being written aside for a path, its bytes appended in order.
  class Aside
  {
  public:
    void append(std::string_view bytes);

  private:
    friend class AtomicWrite;
    std::ofstream Out;
    std::string Path, Written; // where it goes; where it is written aside
    std::string Unmade;        // why its folder could not be made, if it could not
  };
  explicit AtomicWrite(bool overwrite);
  ~AtomicWrite(); // removes what was written aside and not committed
  /// Opens the file written aside for path. Throws FileError when path exists and overwrite is
  /// not set.
  Aside open(const std::string& path);
  /// Closes it; returns the file written aside (a binary format edits it there through its
  /// library before the commit). Throws FileError when it could not be written.
  std::string close(Aside& aside);
  /// Writes bytes aside for path (open, append, close).
  std::string add(const std::string& path, std::string_view bytes);
  /// Renames every file written aside into place, the first added last: once it is in place,
  /// so are the others (a variant interrupted before has no main file, and is written again).
  void commit();

private:
  bool Overwrite;
  std::vector<std::pair<std::string, std::string>> Pending; // (aside, path)
};

/// Whether [first, last) is wholly an integer ("+" allowed), and its value.
bool parseInteger(const char* first, const char* last, std::int64_t& value);

/// Whether [first, last) is wholly a finite real ("+" allowed, and Fortran's "D" exponent), and its
/// value; NaN, infinities and numbers out of a double's range are not.
bool parseReal(const char* first, const char* last, double& value);

/// Appends the shortest text that reads back as the same double; when that is wider than width
/// characters, the closest text of as many significant digits as fit (a relative change below
/// 1e-13 for width 20: the field width CalculiX and Abaqus read a number in).
void appendShortest(std::string& out, double value, std::size_t width = 32);

/// Whether c is a blank within a line (a space or a tab).
inline bool isBlank(char c)
{
  return c == ' ' || c == '\t';
}

/// text without its leading and trailing blanks.
std::string_view trim(std::string_view text);

/// The fields of text between blanks (spaces and tabs), into fields.
void splitBlanks(std::string_view text, std::vector<std::string_view>& fields);

/// Appends the count numbers separated by blanks or line ends that start at text[begin] (a number
/// also ends at a parenthesis: Fluent's "0 0 1))") with the values xyz: a number whose value changed becomes appendShortest's text of the new one, the
/// others and what separates them stay as they were. Returns where the last number's text ends.
std::size_t appendNumbers(std::string& out, std::string_view text, std::size_t begin, int count, const double* xyz);

/// Appends the count binary numbers of type T (in the machine's byte order) that start at text[at]
/// with the values xyz: a number whose value changed becomes the new value as a T, the others stay
/// as they were. Returns where the last number ends.
template <class T>
std::size_t appendBinaryNumbers(std::string& out, std::string_view text, std::size_t at, int count, const double* xyz)
{
  for (int c = 0; c < count; ++c, at += sizeof(T))
  {
    T number;
    std::memcpy(&number, text.data() + at, sizeof(T));
    if (static_cast<double>(number) != xyz[c])
    {
      number = static_cast<T>(xyz[c]);
    }
    out.append(reinterpret_cast<const char*>(&number), sizeof(T));
  }
  return at;
}

/// The line of text at `at` (without "\n" or "\r\n"), `at` moved to the next; false at the end.
bool nextLine(std::string_view text, std::size_t& at, std::string_view& line);

/// The lines of text: the offsets where each line starts and ends (without "\n" or "\r\n").
struct Line
{
  std::size_t begin, end, next;
};
std::vector<Line> lines(std::string_view text);
} // namespace mlsformats
