// What every format's reading and writing shares: an error that names the file and the line,
// a whole file read at once, a file written aside and renamed into place (never half-written),
// and the shortest text of a double that reads back as the same double.
#pragma once

#include <cstdint>
#include <cstring>
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

/// The file's first bytes (fewer when it is shorter, none when it cannot be read): what tells
/// its format.
std::string readHead(const std::string& path, std::size_t bytes);

/// An open file's descriptor, closed with its owner (moved, never copied).
class Descriptor
{
public:
  explicit Descriptor(int descriptor = -1)
    : Value(descriptor)
  {
  }
  Descriptor(Descriptor&& other) noexcept
    : Value(other.Value)
  {
    other.Value = -1;
  }
  Descriptor& operator=(Descriptor&& other) noexcept
  {
    if (this != &other)
    {
      this->close();
      this->Value = other.Value;
      other.Value = -1;
    }
    return *this;
  }
  ~Descriptor() { this->close(); }
  int get() const { return this->Value; }
  /// Closes it now; false when that fails (bytes written that did not reach the file).
  bool close();

private:
  int Value;
};

/// A source file read to write a variant of it, in file order and never mapped: the span that
/// holds its nodes read into memory (read), every other span read in chunks and written on
/// (AtomicWrite::Aside::copy). Its bytes are hashed as they pass: once the last has, a hash other
/// than the one they had when the file was read throws FileError ("has changed since it was
/// read"), before the variant is committed. Not mapped: a file truncated meanwhile (a mesher
/// writing it again in place) is a FileError, not the end of the process.
class SourceBytes
{
public:
  /// hash: contentHash of the file as it was read; noun: what to read again ("mesh", "deck").
  SourceBytes(const std::string& path, std::size_t hash, const char* noun = "mesh");
  const std::string& path() const { return this->Path; }
  std::size_t size() const { return this->Size; }
  /// The next bytes, [begin, end) (begin: where those read or copied so far end), read into
  /// memory and held until the next read.
  std::string_view read(std::size_t begin, std::size_t end);

private:
  friend class AtomicWrite;
  void readInto(char* data, std::size_t begin, std::size_t end); // throws when the file ends first
  void pass(std::string_view bytes);                               // hashes the next bytes
  std::string Path;
  const char* Noun;
  Descriptor File;
  std::size_t Size = 0, Expected = 0;
  std::size_t Next = 0;              // where the bytes passed so far end
  std::vector<std::size_t> Chunks;   // the hashes of the chunks passed
  std::string Partial;               // the bytes of the chunk being passed, unless passed whole
  std::string Bytes, Buffer;         // the span read last; a chunk on its way
};

/// contentHash of the file at path, read chunk by chunk side by side. Throws FileError.
std::size_t fileHash(const std::string& path);

/// The hash of a file's bytes, taken when it is read and checked before a variant is written from
/// it (SourceBytes checks it as the bytes pass: a variant is written from the bytes that were
/// read, or not at all).
std::size_t contentHash(std::string_view bytes);

/// The files written into place at once: each is written aside (path.writing-<process>), and only
/// once all are written are they renamed into place; a failure removes what was written aside and
/// throws FileError. Existing files are replaced only when overwrite is set (else FileError).
class AtomicWrite
{
public:
  /// A file being written aside for a path, its bytes appended in order. A failure to write is
  /// kept and thrown by AtomicWrite::close (append is called where nothing may throw: in order,
  /// from the threads that format a variant's pieces).
  class Aside
  {
  public:
    void append(std::string_view bytes);
    /// Appends source's next bytes, [begin, end). Throws FileError naming the source when it
    /// ends before end or, its last bytes passed, has changed since it was read.
    void copy(SourceBytes& source, std::size_t begin, std::size_t end);

  private:
    friend class AtomicWrite;
    Descriptor File;
    std::string Path, Written; // where it goes; where it is written aside
    std::string Failure;       // why it could not be written, once it could not
  };
  explicit AtomicWrite(bool overwrite);
  ~AtomicWrite(); // removes what was written aside and not committed, and the folders made for it
  /// Opens the file written aside for path. Throws FileError when path exists and overwrite is
  /// not set.
  Aside open(const std::string& path);
  /// Closes it; returns the file written aside (a binary format edits it there through its
  /// library before the commit). Throws FileError when it could not be written.
  std::string close(Aside& aside);
  /// Writes bytes aside for path (open, append, close).
  std::string add(const std::string& path, std::string_view bytes);
  /// Writes a copy of source aside for path (open, copy, close).
  std::string add(const std::string& path, SourceBytes& source);
  /// Renames every file written aside into place, the first added last: once it is in place,
  /// so are the others (a variant interrupted before has no main file, and is written again).
  void commit();

private:
  bool Overwrite;
  std::vector<std::pair<std::string, std::string>> Pending; // (aside, path)
  std::vector<std::string> Made;                            // the folders made for them
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
/// also ends at a parenthesis: Fluent's "0 0 1))") with the values xyz: a number whose value
/// changed becomes appendShortest's text of the new one, the others and what separates them stay
/// as they were. old: their values as read (nullptr: parsed from their text). Returns where the
/// last number's text ends.
std::size_t appendNumbers(
  std::string& out, std::string_view text, std::size_t begin, int count, const double* xyz, const double* old = nullptr);

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
