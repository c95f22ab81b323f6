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

namespace mlsdeform
{
namespace
{
[[noreturn]] void fail(const std::string& path, const std::string& reason)
{
  throw std::runtime_error(path + ": " + reason);
}

// The whole file, decompressed if it is gzip (zlib reads plain files unchanged).
std::string readAll(const std::string& path)
{
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file)
  {
    fail(path, "cannot be opened");
  }
  std::string content;
  char buffer[1 << 16];
  int read = 0;
  while ((read = gzread(file, buffer, sizeof(buffer))) > 0)
  {
    content.append(buffer, static_cast<std::size_t>(read));
  }
  const bool failed = read < 0;
  gzclose(file);
  if (failed)
  {
    fail(path, "cannot be read (a damaged gzip file?)");
  }
  return content;
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
} // namespace

FoamPointsFile readFoamPoints(const std::string& polyMeshDirectory)
{
  FoamPointsFile file;
  file.path = polyMeshDirectory + "/points";
  if (!std::filesystem::exists(file.path))
  {
    file.path += ".gz";
    file.compressed = true;
    if (!std::filesystem::exists(file.path))
    {
      fail(polyMeshDirectory + "/points", "there is no points file (nor points.gz): not an OpenFOAM polyMesh directory");
    }
  }
  const std::string s = readAll(file.path);
  const std::size_t foamFile = s.find("FoamFile");
  const std::size_t open = foamFile == std::string::npos ? foamFile : s.find('{', foamFile);
  const std::size_t close = open == std::string::npos ? open : s.find('}', open);
  if (close == std::string::npos)
  {
    fail(file.path, "no FoamFile header");
  }
  const std::string dictionary = s.substr(open + 1, close - open - 1);
  if (entry(dictionary, "class") != "vectorField")
  {
    fail(file.path, "its class is '" + entry(dictionary, "class") + "', not vectorField");
  }
  const std::string format = entry(dictionary, "format");
  if (format != "ascii" && format != "binary")
  {
    fail(file.path, "unknown format '" + format + "'");
  }
  file.binary = format == "binary";
  const std::string arch = entry(dictionary, "arch");
  if (arch.find("scalar=32") != std::string::npos)
  {
    file.scalarBytes = 4;
  }
  if (file.binary && arch.find("MSB") != std::string::npos)
  {
    fail(file.path, "big-endian binary files are not supported");
  }
  std::size_t i = skipBlank(s, close + 1);
  file.header = s.substr(0, i);
  char* end = nullptr;
  const long long count = std::strtoll(s.c_str() + i, &end, 10);
  if (end == s.c_str() + i || count < 0)
  {
    fail(file.path, "no point count after the header");
  }
  // the count must fit the file: at least 3 bytes per binary scalar, 7 characters per ascii point
  const std::size_t available = s.size() - i;
  if (static_cast<unsigned long long>(count) > available / (file.binary ? 3 * file.scalarBytes : 7))
  {
    fail(file.path, "the point count " + std::to_string(count) + " does not fit the file's size");
  }
  i = skipBlank(s, static_cast<std::size_t>(end - s.c_str()));
  if (i >= s.size() || s[i] != '(')
  {
    fail(file.path, "no '(' after the point count (a uniform list is not a mesh)");
  }
  ++i;
  const std::size_t n = static_cast<std::size_t>(count);
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
      char* next = nullptr;
      file.xyz[3 * k + c] = std::strtod(p, &next);
      if (next == p)
      {
        fail(file.path, "point " + std::to_string(k) + " has no coordinate " + std::to_string(c));
      }
      p = next;
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

void writeFoamPoints(const std::string& directory, const FoamPointsFile& original, const std::vector<double>& xyz)
{
  const std::size_t n = xyz.size() / 3;
  std::string out = original.header + std::to_string(n) + "\n(";
  if (original.binary)
  {
    for (double value : xyz)
    {
      char bytes[8];
      if (original.scalarBytes == 8)
      {
        std::memcpy(bytes, &value, 8);
      }
      else
      {
        const float single = static_cast<float>(value);
        std::memcpy(bytes, &single, 4);
      }
      out.append(bytes, static_cast<std::size_t>(original.scalarBytes));
    }
  }
  else
  {
    out += '\n';
    char number[32];
    for (std::size_t k = 0; k < n; ++k)
    {
      out += '(';
      for (int c = 0; c < 3; ++c)
      {
        // shortest text that reads back as the same double (float for scalar=32)
        const auto written = original.scalarBytes == 8 ? std::to_chars(number, number + sizeof(number), xyz[3 * k + c])
                                                       : std::to_chars(number, number + sizeof(number), static_cast<float>(xyz[3 * k + c]));
        out.append(number, written.ptr);
        out += c < 2 ? ' ' : ')';
      }
      out += '\n';
    }
  }
  out += ")\n\n\n// ************************************************************************* //\n";
  const std::string path = directory + (original.compressed ? "/points.gz" : "/points");
  if (original.compressed)
  {
    gzFile file = gzopen(path.c_str(), "wb");
    if (!file)
    {
      fail(path, "cannot be created");
    }
    bool written = true;
    for (std::size_t at = 0; written && at < out.size(); at += 1 << 24)
    {
      const unsigned chunk = static_cast<unsigned>(std::min<std::size_t>(out.size() - at, 1 << 24));
      written = gzwrite(file, out.data() + at, chunk) == static_cast<int>(chunk);
    }
    if (gzclose(file) != Z_OK || !written)
    {
      fail(path, "cannot be written");
    }
    return;
  }
  std::ofstream file(path, std::ios::binary);
  file.write(out.data(), static_cast<std::streamsize>(out.size()));
  file.close();
  if (!file)
  {
    fail(path, "cannot be written");
  }
}
} // namespace mlsdeform
