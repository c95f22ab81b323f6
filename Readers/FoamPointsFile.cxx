#include "FoamPointsFile.h"

#include <vtk_zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

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

// A FoamFile list file (points, pointProcAddressing) read up to its first element.
struct FoamList
{
  std::string text;   // the whole file, decompressed
  std::string header; // everything before the count
  bool binary = false;
  std::string arch;   // e.g. LSB;label=32;scalar=64
  std::size_t count = 0;
  std::size_t begin = 0; // the position after '('
};

// Reads path and checks its class; elementBytes: the least bytes of one element in binary and in
// ascii, so that a count that cannot fit the file is an error before anything is allocated.
FoamList readList(const std::string& path, const std::string& expectedClass, std::size_t binaryBytes, std::size_t asciiBytes)
{
  FoamList list;
  list.text = readAll(path);
  const std::string& s = list.text;
  const std::size_t foamFile = s.find("FoamFile");
  const std::size_t open = foamFile == std::string::npos ? foamFile : s.find('{', foamFile);
  const std::size_t close = open == std::string::npos ? open : s.find('}', open);
  if (close == std::string::npos)
  {
    fail(path, "no FoamFile header");
  }
  const std::string dictionary = s.substr(open + 1, close - open - 1);
  if (entry(dictionary, "class") != expectedClass)
  {
    fail(path, "its class is '" + entry(dictionary, "class") + "', not " + expectedClass);
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
  std::size_t i = skipBlank(s, close + 1);
  list.header = s.substr(0, i);
  char* end = nullptr;
  const long long count = std::strtoll(s.c_str() + i, &end, 10);
  if (end == s.c_str() + i || count < 0)
  {
    fail(path, "no element count after the header");
  }
  if (static_cast<unsigned long long>(count) > (s.size() - i) / (list.binary ? binaryBytes : asciiBytes))
  {
    fail(path, "the count " + std::to_string(count) + " does not fit the file's size");
  }
  i = skipBlank(s, static_cast<std::size_t>(end - s.c_str()));
  if (i >= s.size() || s[i] != '(')
  {
    fail(path, "no '(' after the count (a uniform list is not a mesh)");
  }
  list.count = static_cast<std::size_t>(count);
  list.begin = i + 1;
  return list;
}

// The file directory/name, or directory/name.gz; "" when there is neither.
std::string existing(const std::string& directory, const std::string& name)
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
} // namespace

FoamPointsFile readFoamPoints(const std::string& polyMeshDirectory)
{
  FoamPointsFile file;
  file.path = existing(polyMeshDirectory, "points");
  if (file.path.empty())
  {
    fail(polyMeshDirectory + "/points", "there is no points file (nor points.gz): not an OpenFOAM polyMesh directory");
  }
  file.compressed = file.path.size() > 3 && file.path.compare(file.path.size() - 3, 3, ".gz") == 0;
  // a binary scalar has 4 bytes at least, an ascii point "(x y z)" 7 characters
  const FoamList list = readList(file.path, "vectorField", 3 * 4, 7);
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
    while (p < last && std::isspace(static_cast<unsigned char>(*p)))
    {
      ++p;
    }
    if (p >= last || *p != '(')
    {
      fail(file.path, "point " + std::to_string(k) + " is not '(x y z)'");
    }
    ++p;
    for (int c = 0; c < 3; ++c)
    {
      if (!readNumber(p, last, file.xyz[3 * k + c]))
      {
        fail(file.path, "point " + std::to_string(k) + " has no coordinate " + std::to_string(c));
      }
    }
    while (p < last && std::isspace(static_cast<unsigned char>(*p)))
    {
      ++p;
    }
    if (p >= last || *p != ')')
    {
      fail(file.path, "point " + std::to_string(k) + " is not '(x y z)'");
    }
    ++p;
  }
  return file;
}

std::vector<std::int64_t> readFoamLabels(const std::string& polyMeshDirectory, const std::string& name)
{
  const std::string path = existing(polyMeshDirectory, name);
  if (path.empty())
  {
    fail(polyMeshDirectory + "/" + name, "there is no such file (nor " + name + ".gz)");
  }
  // a binary label has 4 bytes at least, an ascii one 2 characters with its separator
  const FoamList list = readList(path, "labelList", 4, 2);
  const std::size_t labelBytes = list.arch.find("label=64") != std::string::npos ? 8 : 4;
  const std::string& s = list.text;
  std::vector<std::int64_t> labels(list.count);
  if (list.binary)
  {
    if (list.begin + labelBytes * list.count >= s.size() || s[list.begin + labelBytes * list.count] != ')')
    {
      fail(path, "the binary list of " + std::to_string(list.count) + " labels is truncated");
    }
    for (std::size_t k = 0; k < list.count; ++k)
    {
      if (labelBytes == 8)
      {
        std::memcpy(&labels[k], s.data() + list.begin + 8 * k, 8);
      }
      else
      {
        std::int32_t label;
        std::memcpy(&label, s.data() + list.begin + 4 * k, 4);
        labels[k] = label;
      }
    }
    return labels;
  }
  const char* p = s.c_str() + list.begin;
  const char* last = s.c_str() + s.size();
  for (std::size_t k = 0; k < list.count; ++k)
  {
    if (!readNumber(p, last, labels[k]))
    {
      fail(path, "label " + std::to_string(k) + " is not a number");
    }
  }
  return labels;
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
