#include "Foam/PolyMeshFiles.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace mlsfoam
{
namespace
{
[[noreturn]] void fail(const std::string& path, const std::string& reason)
{
  throw std::runtime_error(path + ": " + reason);
}

// The whole file, decompressed if it is gzip (zlib reads plain files unchanged), read into a
// string sized by the file (a plain file's exact size, at least that for gzip) rather than grown
// by appending: the mesh's points are tens of MB.
std::string readAll(const std::string& path)
{
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file)
  {
    fail(path, "cannot be opened");
  }
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  std::string content(error ? std::size_t(1) << 16 : static_cast<std::size_t>(size) + 1, '\0');
  std::size_t length = 0;
  int read = 0;
  do
  {
    if (length == content.size())
    {
      content.resize(2 * content.size());
    }
    const unsigned chunk = static_cast<unsigned>(std::min<std::size_t>(content.size() - length, 1 << 30));
    read = gzread(file, &content[length], chunk);
    length += read > 0 ? static_cast<std::size_t>(read) : 0;
  } while (read > 0);
  const bool failed = read < 0;
  gzclose(file);
  if (failed)
  {
    fail(path, "cannot be read (a damaged gzip file?)");
  }
  content.resize(length);
  return content;
}

// Reads the number after white space at p (before last) into value and moves p past it; false
// when there is none. std::from_chars: a few times faster than strtod on a mesh's millions.
template <typename Number>
bool readNumber(const char*& p, const char* last, Number& value)
{
  while (p < last && std::isspace(static_cast<unsigned char>(*p)))
  {
    ++p;
  }
  if (p + 1 < last && *p == '+' && *(p + 1) != '-') // strtod's optional plus sign
  {
    ++p;
  }
  const auto [next, error] = std::from_chars(p, last, value);
  if (error != std::errc() || next == p)
  {
    return false;
  }
  p = next;
  return true;
}

// Moves p past white space and the character c; false (p past the white space) when c is not next.
bool passed(const char*& p, const char* last, char c)
{
  while (p < last && std::isspace(static_cast<unsigned char>(*p)))
  {
    ++p;
  }
  if (p >= last || *p != c)
  {
    return false;
  }
  ++p;
  return true;
}

// Skips white space and C/C++ comments from position i.
std::size_t skipBlank(const std::string& s, std::size_t i)
{
  while (i < s.size())
  {
    if (std::isspace(static_cast<unsigned char>(s[i])))
    {
      ++i;
    }
    else if (s.compare(i, 2, "//") == 0)
    {
      i = s.find('\n', i);
      i = i == std::string::npos ? s.size() : i + 1;
    }
    else if (s.compare(i, 2, "/*") == 0)
    {
      i = s.find("*/", i + 2);
      i = i == std::string::npos ? s.size() : i + 2;
    }
    else
    {
      break;
    }
  }
  return i;
}

// The value of keyword in the FoamFile dictionary text (without quotes and ';'), or "".
std::string entry(const std::string& dictionary, const std::string& keyword)
{
  std::size_t at = 0;
  while ((at = dictionary.find(keyword, at)) != std::string::npos)
  {
    const bool wordStart = at == 0 || std::isspace(static_cast<unsigned char>(dictionary[at - 1])) || dictionary[at - 1] == '{';
    const std::size_t after = at + keyword.size();
    if (wordStart && after < dictionary.size() && std::isspace(static_cast<unsigned char>(dictionary[after])))
    {
      // a quoted value (arch "LSB;label=32;scalar=64") may hold ';'
      std::size_t begin = after;
      while (begin < dictionary.size() && std::isspace(static_cast<unsigned char>(dictionary[begin])))
      {
        ++begin;
      }
      const bool quoted = begin < dictionary.size() && dictionary[begin] == '"';
      const std::size_t end = quoted ? dictionary.find('"', begin + 1) : dictionary.find(';', begin);
      std::string value = dictionary.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
      std::string trimmed;
      for (char c : value)
      {
        if (!std::isspace(static_cast<unsigned char>(c)) && c != '"')
        {
          trimmed += c;
        }
      }
      return trimmed;
    }
    at = after;
  }
  return "";
}

// A FoamFile list file (points, labels, faces) read up to its first element.
struct FoamList
{
  std::string text;   // the whole file, decompressed
  std::string header; // everything before the count
  bool binary = false;
  std::string arch;   // e.g. LSB;label=32;scalar=64
  std::string kind;   // its class
  std::size_t count = 0;
  std::size_t begin = 0; // the position after '('
};

// The FoamFile dictionary of a file's text (between its braces) and the position after it;
// npos when there is none.
std::pair<std::string, std::size_t> headerOf(const std::string& s)
{
  const std::size_t foamFile = s.find("FoamFile");
  const std::size_t open = foamFile == std::string::npos ? foamFile : s.find('{', foamFile);
  const std::size_t close = open == std::string::npos ? open : s.find('}', open);
  if (close == std::string::npos)
  {
    return { std::string(), std::string::npos };
  }
  return { s.substr(open + 1, close - open - 1), close + 1 };
}

// The count of a list that starts at s[i] ("count(") and the position after its '('; a count
// that cannot fit the rest of the file (elementBytes each at least) is an error.
std::pair<std::size_t, std::size_t> openList(const std::string& path, const std::string& s, std::size_t i, std::size_t elementBytes)
{
  char* end = nullptr;
  const long long count = i < s.size() ? std::strtoll(s.c_str() + i, &end, 10) : -1;
  if (end == nullptr || end == s.c_str() + i || count < 0)
  {
    fail(path, "no element count at byte " + std::to_string(i));
  }
  if (static_cast<unsigned long long>(count) > (s.size() - i) / elementBytes)
  {
    fail(path, "the list of " + std::to_string(count) + " elements does not fit the file's size (truncated)");
  }
  i = skipBlank(s, static_cast<std::size_t>(end - s.c_str()));
  if (i >= s.size() || s[i] != '(')
  {
    fail(path, "no '(' after the count " + std::to_string(count) + " (a uniform list is not a mesh)");
  }
  return { static_cast<std::size_t>(count), i + 1 };
}

// Reads path and checks its class (one of classes); elementBytes: the least bytes of one element in binary and in
// ascii, so that a count that cannot fit the file is an error before anything is allocated.
FoamList readList(
  const std::string& path, const std::vector<std::string>& classes, std::size_t binaryBytes, std::size_t asciiBytes)
{
  FoamList list;
  list.text = readAll(path);
  const std::string& s = list.text;
  const auto [dictionary, afterHeader] = headerOf(s);
  if (afterHeader == std::string::npos)
  {
    fail(path, "no FoamFile header");
  }
  list.kind = entry(dictionary, "class");
  if (std::find(classes.begin(), classes.end(), list.kind) == classes.end())
  {
    std::string expected;
    for (const std::string& c : classes)
    {
      expected += (expected.empty() ? "" : " or ") + c;
    }
    fail(path, "its class is '" + list.kind + "', not " + expected);
  }
  const std::string format = entry(dictionary, "format");
  if (format != "ascii" && format != "binary")
  {
    fail(path, "unknown format '" + format + "'");
  }
  list.binary = format == "binary";
  list.arch = entry(dictionary, "arch");
  if (list.binary && list.arch.find("MSB") != std::string::npos)
  {
    fail(path, "big-endian binary files are not supported");
  }
  const std::size_t i = skipBlank(s, afterHeader);
  list.header = s.substr(0, i);
  std::tie(list.count, list.begin) = openList(path, s, i, list.binary ? binaryBytes : asciiBytes);
  return list;
}

} // namespace

namespace
{
// The words and delimiters ({ } ( ) ;) of a dictionary's text from position i, without comments;
// a quoted string is one word, without its quotes.
std::vector<std::string> dictionaryTokens(const std::string& s, std::size_t i)
{
  std::vector<std::string> tokens;
  const auto delimiter = [](char c) { return c == '{' || c == '}' || c == '(' || c == ')' || c == ';'; };
  while ((i = skipBlank(s, i)) < s.size())
  {
    if (delimiter(s[i]))
    {
      tokens.emplace_back(1, s[i++]);
    }
    else if (s[i] == '"')
    {
      const std::size_t end = s.find('"', i + 1);
      tokens.push_back(s.substr(i + 1, end == std::string::npos ? std::string::npos : end - i - 1));
      i = end == std::string::npos ? s.size() : end + 1;
    }
    else
    {
      const std::size_t begin = i;
      while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i])) && !delimiter(s[i]) && s.compare(i, 2, "//") != 0 &&
        s.compare(i, 2, "/*") != 0)
      {
        ++i;
      }
      tokens.push_back(s.substr(begin, i - begin));
    }
  }
  return tokens;
}
}

std::vector<FoamPatch> readFoamBoundary(const std::string& polyMeshDirectory)
{
  const std::string path = foamFile(polyMeshDirectory, "boundary");
  if (path.empty())
  {
    fail(polyMeshDirectory + "/boundary", "no such file");
  }
  const std::string s = readAll(path);
  const auto [dictionary, afterHeader] = headerOf(s);
  if (afterHeader == std::string::npos || entry(dictionary, "class") != "polyBoundaryMesh")
  {
    fail(path, "not a polyBoundaryMesh (no FoamFile header of that class)");
  }
  // [count] ( name { key value; ... } ... )
  const std::vector<std::string> t = dictionaryTokens(s, afterHeader);
  std::size_t k = 0;
  if (k < t.size() && !t[k].empty() && std::isdigit(static_cast<unsigned char>(t[k][0])))
  {
    ++k;
  }
  if (k >= t.size() || t[k] != "(")
  {
    fail(path, "no list of patches");
  }
  std::vector<FoamPatch> patches;
  for (++k; k < t.size() && t[k] != ")";)
  {
    FoamPatch patch;
    patch.name = t[k++];
    if (k >= t.size() || t[k] != "{")
    {
      fail(path, "patch " + patch.name + " has no dictionary");
    }
    // its entries: a key, then tokens up to ';' at this depth (nested dictionaries and lists skipped)
    int depth = 1;
    for (++k; k < t.size() && depth > 0;)
    {
      if (t[k] == "}")
      {
        --depth;
        ++k;
        continue;
      }
      const std::string key = t[k++];
      std::vector<std::string> value;
      int inner = 0;
      const bool subDictionary = k < t.size() && t[k] == "{"; // ends at its '}', with no ';'
      for (; k < t.size() && !(inner == 0 && (t[k] == ";" || t[k] == "}")); ++k)
      {
        inner += (t[k] == "{" || t[k] == "(") ? 1 : (t[k] == "}" || t[k] == ")") ? -1 : 0;
        value.push_back(t[k]);
        if (subDictionary && inner == 0)
        {
          ++k;
          break;
        }
      }
      k += (k < t.size() && t[k] == ";") ? 1 : 0;
      if (key == "type" && value.size() == 1)
      {
        patch.type = value[0];
      }
      else if (key == "inGroups")
      {
        // List<word> 2(wall motorBikeGroup), 2(wall motorBikeGroup) or (wall)
        bool inside = false;
        for (const std::string& word : value)
        {
          if (word == "(" || word == ")")
          {
            inside = word == "(";
          }
          else if (inside)
          {
            patch.groups.push_back(word);
          }
        }
      }
    }
    if (depth != 0)
    {
      fail(path, "patch " + patch.name + "'s dictionary is not closed (truncated)");
    }
    patches.push_back(std::move(patch));
  }
  if (k >= t.size())
  {
    fail(path, "the list of patches is not closed (truncated)");
  }
  return patches;
}

std::string foamFile(const std::string& directory, const std::string& name)
{
  for (const std::string& path : { directory + "/" + name, directory + "/" + name + ".gz" })
  {
    if (std::filesystem::exists(path))
    {
      return path;
    }
  }
  return "";
}

FoamPointsFile readFoamPoints(const std::string& polyMeshDirectory)
{
  FoamPointsFile file;
  file.path = foamFile(polyMeshDirectory, "points");
  if (file.path.empty())
  {
    fail(polyMeshDirectory + "/points", "there is no points file (nor points.gz): not an OpenFOAM polyMesh directory");
  }
  file.compressed = file.path.size() > 3 && file.path.compare(file.path.size() - 3, 3, ".gz") == 0;
  // a binary scalar has 4 bytes at least, an ascii point "(x y z)" 7 characters
  const FoamList list = readList(file.path, { "vectorField" }, 3 * 4, 7);
  file.scalarBytes = list.arch.find("scalar=32") != std::string::npos ? 4 : 8;
  file.binary = list.binary;
  file.header = list.header;
  const std::string& s = list.text;
  std::size_t i = list.begin;
  const std::size_t n = list.count;
  file.xyz.resize(3 * n);
  if (file.binary)
  {
    const std::size_t bytes = 3 * n * static_cast<std::size_t>(file.scalarBytes);
    if (i + bytes >= s.size() || s[i + bytes] != ')')
    {
      fail(file.path, "the binary list of " + std::to_string(n) + " points is truncated");
    }
    for (std::size_t k = 0; k < 3 * n; ++k)
    {
      if (file.scalarBytes == 8)
      {
        std::memcpy(&file.xyz[k], s.data() + i + 8 * k, 8);
      }
      else
      {
        float value;
        std::memcpy(&value, s.data() + i + 4 * k, 4);
        file.xyz[k] = value;
      }
    }
    return file;
  }
  const char* p = s.c_str() + i;
  const char* last = s.c_str() + s.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!passed(p, last, '('))
    {
      fail(file.path, "point " + std::to_string(k) + " is not '(x y z)'");
    }
    for (int c = 0; c < 3; ++c)
    {
      if (!readNumber(p, last, file.xyz[3 * k + c]))
      {
        fail(file.path, "point " + std::to_string(k) + " has no coordinate " + std::to_string(c));
      }
    }
    if (!passed(p, last, ')'))
    {
      fail(file.path, "point " + std::to_string(k) + " is not '(x y z)'");
    }
  }
  return file;
}

namespace
{
// The count labels of a list whose first element is at s[begin] (after its '('), binary (of
// labelBytes each) or ascii, into labels; returns the position after its ')'. Labels that do not
// fit Label are an error.
template <typename Label>
std::size_t readLabels(const std::string& path, const std::string& s, std::size_t begin, std::size_t count, bool binary,
  std::size_t labelBytes, std::vector<Label>& labels)
{
  labels.resize(count);
  if (binary)
  {
    if (begin + labelBytes * count >= s.size() || s[begin + labelBytes * count] != ')')
    {
      fail(path, "the binary list of " + std::to_string(count) + " labels is truncated");
    }
    for (std::size_t k = 0; k < count; ++k)
    {
      std::int64_t label;
      if (labelBytes == 8)
      {
        std::memcpy(&label, s.data() + begin + 8 * k, 8);
      }
      else
      {
        std::int32_t label32;
        std::memcpy(&label32, s.data() + begin + 4 * k, 4);
        label = label32;
      }
      if (label < std::numeric_limits<Label>::min() || label > std::numeric_limits<Label>::max())
      {
        fail(path, "label " + std::to_string(k) + " (" + std::to_string(label) + ") is out of range");
      }
      labels[k] = static_cast<Label>(label);
    }
    return begin + labelBytes * count + 1;
  }
  const char* p = s.c_str() + begin;
  const char* last = s.c_str() + s.size();
  for (std::size_t k = 0; k < count; ++k)
  {
    if (!readNumber(p, last, labels[k]))
    {
      fail(path, "label " + std::to_string(k) + " is not a number (or out of range)");
    }
  }
  const std::size_t close = skipBlank(s, static_cast<std::size_t>(p - s.c_str()));
  if (close >= s.size() || s[close] != ')')
  {
    fail(path, "the list of " + std::to_string(count) + " labels has no ')' after its last");
  }
  return close + 1;
}

std::size_t labelBytesOf(const FoamList& list)
{
  return list.arch.find("label=64") != std::string::npos ? 8 : 4;
}

// The labelList file name (or name.gz) of a polyMesh directory.
template <typename Label>
std::vector<Label> readLabelList(const std::string& polyMeshDirectory, const std::string& name)
{
  const std::string path = foamFile(polyMeshDirectory, name);
  if (path.empty())
  {
    fail(polyMeshDirectory + "/" + name, "there is no such file (nor " + name + ".gz)");
  }
  // a binary label has 4 bytes at least, an ascii one 2 characters with its separator
  const FoamList list = readList(path, { "labelList" }, 4, 2);
  std::vector<Label> labels;
  readLabels(path, list.text, list.begin, list.count, list.binary, labelBytesOf(list), labels);
  return labels;
}
} // namespace

std::vector<std::int64_t> readFoamLabels(const std::string& polyMeshDirectory, const std::string& name)
{
  return readLabelList<std::int64_t>(polyMeshDirectory, name);
}

std::vector<int> readFoamIndices(const std::string& polyMeshDirectory, const std::string& name)
{
  return readLabelList<int>(polyMeshDirectory, name);
}

bool isTimeName(const std::string& name)
{
  char* end = nullptr;
  std::strtod(name.c_str(), &end);
  return !name.empty() && *end == '\0';
}

FoamMeshSize readFoamMeshSize(const std::string& polyMeshDirectory)
{
  FoamMeshSize size;
  const std::string path = foamFile(polyMeshDirectory, "owner");
  gzFile file = path.empty() ? nullptr : gzopen(path.c_str(), "rb");
  if (!file)
  {
    return size;
  }
  std::string head(4096, '\0'); // the header: a FoamFile dictionary of a few lines
  const int read = gzread(file, &head[0], static_cast<unsigned>(head.size()));
  gzclose(file);
  head.resize(read > 0 ? static_cast<std::size_t>(read) : 0);
  const std::string note = entry(headerOf(head).first, "note"); // blanks removed
  for (auto [key, value] : { std::pair<const char*, long long*>{ "nPoints:", &size.points }, { "nCells:", &size.cells } })
  {
    const std::size_t at = note.find(key);
    if (at != std::string::npos)
    {
      *value = std::strtoll(note.c_str() + at + std::strlen(key), nullptr, 10);
    }
  }
  return size;
}

FoamFaces readFoamFaces(const std::string& polyMeshDirectory)
{
  const std::string path = foamFile(polyMeshDirectory, "faces");
  if (path.empty())
  {
    fail(polyMeshDirectory + "/faces", "there is no faces file (nor faces.gz)");
  }
  FoamFaces faces;
  // binary faces are a faceCompactList (the offsets, then the points); ascii ones a faceList
  // ("4(0 1 2 3)" each) or a faceCompactList
  const FoamList list = readList(path, { "faceCompactList", "faceList" }, 4, 2);
  const std::string& s = list.text;
  const std::size_t labelBytes = labelBytesOf(list);
  if (list.kind == "faceCompactList")
  {
    // the offsets (faces + 1), then "count(" and the points
    const std::size_t after = skipBlank(s, readLabels(path, s, list.begin, list.count, list.binary, labelBytes, faces.start));
    const auto [count, begin] = openList(path, s, after, list.binary ? labelBytes : 2);
    readLabels(path, s, begin, count, list.binary, labelBytes, faces.points);
    if (faces.start.empty() || faces.start.front() != 0 || faces.start.back() != static_cast<int>(faces.points.size()) ||
      !std::is_sorted(faces.start.begin(), faces.start.end()))
    {
      fail(path, "the faces' offsets do not run from 0 to the number of points in order");
    }
    return faces;
  }
  if (list.binary)
  {
    fail(path, "a binary faceList (OpenFOAM writes binary faces as a faceCompactList)");
  }
  const char* p = s.c_str() + list.begin;
  const char* last = s.c_str() + s.size();
  faces.start.reserve(list.count + 1);
  for (std::size_t f = 0; f < list.count; ++f)
  {
    int n = 0;
    if (!readNumber(p, last, n) || n < 0 || !passed(p, last, '('))
    {
      fail(path, "face " + std::to_string(f) + " is not 'n(p0 p1 ...)'");
    }
    for (int k = 0; k < n; ++k)
    {
      int point = 0;
      if (!readNumber(p, last, point))
      {
        fail(path, "face " + std::to_string(f) + " has no point " + std::to_string(k));
      }
      faces.points.push_back(point);
    }
    if (!passed(p, last, ')'))
    {
      fail(path, "face " + std::to_string(f) + " has more points than its count");
    }
    faces.start.push_back(static_cast<int>(faces.points.size()));
  }
  return faces;
}

namespace
{
// Writes the pieces one after the other into path, gzip-compressed or plain.
void writePieces(const std::string& path, bool compressed, const std::vector<std::pair<const char*, std::size_t>>& pieces)
{
  bool written = true;
  if (compressed)
  {
    gzFile file = gzopen(path.c_str(), "wb");
    if (!file)
    {
      fail(path, "cannot be created");
    }
    for (const auto& [data, size] : pieces)
    {
      for (std::size_t at = 0; written && at < size; at += 1 << 24)
      {
        const unsigned chunk = static_cast<unsigned>(std::min<std::size_t>(size - at, 1 << 24));
        written = gzwrite(file, data + at, chunk) == static_cast<int>(chunk);
      }
    }
    written = gzclose(file) == Z_OK && written;
  }
  else
  {
    std::ofstream file(path, std::ios::binary);
    for (const auto& [data, size] : pieces)
    {
      file.write(data, static_cast<std::streamsize>(size));
    }
    file.close();
    written = static_cast<bool>(file);
  }
  if (!written)
  {
    fail(path, "cannot be written");
  }
}
} // namespace

void writeFoamPoints(const std::string& directory, const FoamPointsFile& original, const std::vector<double>& xyz)
{
  const std::size_t n = xyz.size() / 3;
  const std::string path = directory + (original.compressed ? "/points.gz" : "/points");
  const std::string begin = original.header + std::to_string(n) + "\n(";
  const std::string end = ")\n\n\n// ************************************************************************* //\n";
  std::string list; // the coordinates as text or as 32-bit floats; 64-bit ones are written from xyz itself
  if (original.binary && original.scalarBytes == 4)
  {
    list.resize(4 * xyz.size());
    for (std::size_t k = 0; k < xyz.size(); ++k)
    {
      const float single = static_cast<float>(xyz[k]);
      std::memcpy(&list[4 * k], &single, 4);
    }
  }
  else if (!original.binary)
  {
    // chunks of points formatted in parallel, joined in order
    list += '\n';
    constexpr std::size_t Chunk = 16384;
    std::vector<std::string> parts((n + Chunk - 1) / Chunk);
#pragma omp parallel for schedule(dynamic)
    for (long part = 0; part < static_cast<long>(parts.size()); ++part)
    {
      std::string& text = parts[part];
      text.reserve(Chunk * 3 * 25);
      char number[32];
      for (std::size_t k = part * Chunk; k < std::min(n, (part + 1) * Chunk); ++k)
      {
        text += '(';
        for (int c = 0; c < 3; ++c)
        {
          // shortest text that reads back as the same double (float for scalar=32)
          const auto written = original.scalarBytes == 8 ? std::to_chars(number, number + sizeof(number), xyz[3 * k + c])
                                                         : std::to_chars(number, number + sizeof(number), static_cast<float>(xyz[3 * k + c]));
          text.append(number, written.ptr);
          text += c < 2 ? ' ' : ')';
        }
        text += '\n';
      }
    }
    std::size_t length = list.size();
    for (const std::string& text : parts)
    {
      length += text.size();
    }
    list.reserve(length);
    for (std::string& text : parts)
    {
      list += text;
      std::string().swap(text);
    }
  }
  const bool raw = original.binary && original.scalarBytes == 8; // not copied first: 28.5 MB on a 1M-point mesh
  writePieces(path, original.compressed,
    { { begin.data(), begin.size() },
      raw ? std::make_pair(reinterpret_cast<const char*>(xyz.data()), 8 * xyz.size()) : std::make_pair(list.data(), list.size()),
      { end.data(), end.size() } });
}
} // namespace mlsfoam
