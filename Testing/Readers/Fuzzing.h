// What the readers' fuzz tests share: the mutations they apply to valid seeds (truncation, a token
// replaced by a huge, negative, non-finite or malformed value, binary garbage, flipped bits, a line
// lost or repeated, or nothing of the file left), and an observer that counts a reader's messages.
#pragma once

#include <vtkCommand.h>

#include <algorithm>
#include <iterator>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace testing
{
/// Counts the messages (errors, warnings) of what it observes and keeps the last.
struct LastError : vtkCommand
{
  static LastError* New() { return new LastError; }
  void Execute(vtkObject*, unsigned long, void* message) override
  {
    ++count;
    text = static_cast<const char*>(message);
  }
  int count = 0;
  std::string text;
};

// One random mutation of text.
inline std::string mutate(std::string text, std::mt19937& random)
{
  auto position = [&](std::size_t size) { return std::uniform_int_distribution<std::size_t>(0, size)(random); };
  static const char* tokens[] = { "999999999999", "9223372036854775807", "18446744073709551616", "2147483648", "-1", "-99999", "nan",
    "NaN", "-nan", "inf", "1e400", "-1e400", "0", "1.5", "0x1F", "#", "", "OFF", "\x01\xff", "*", "**", ",", "*INCLUDE", "*NODE",
    "*ELEMENT, TYPE=C3D10", "GENERATE", "1D400" };
  if (text.empty())
  {
    return text;
  }
  switch (std::uniform_int_distribution<int>(0, 5)(random))
  {
    case 0: // truncated anywhere
      return text.substr(0, position(text.size()));
    case 1: // a token replaced by a huge, negative, non-finite or malformed value
    {
      std::vector<std::pair<std::size_t, std::size_t>> spans; // (start, length) of each token
      for (std::size_t i = 0; i < text.size();)
      {
        const std::size_t end = text.find_first_of(" \n,", i);
        const std::size_t stop = end == std::string::npos ? text.size() : end;
        if (stop > i)
          spans.push_back({ i, stop - i });
        i = stop + 1;
      }
      if (spans.empty())
        return text;
      const auto [start, length] = spans[position(spans.size() - 1)];
      return text.replace(start, length, tokens[position(std::size(tokens) - 1)]);
    }
    case 2: // binary garbage inserted
    {
      std::string garbage(std::uniform_int_distribution<int>(1, 64)(random), '\0');
      for (char& c : garbage)
        c = static_cast<char>(std::uniform_int_distribution<int>(0, 255)(random));
      return text.insert(position(text.size()), garbage);
    }
    case 3: // bits flipped
      for (int flips = std::uniform_int_distribution<int>(1, 8)(random); flips > 0; --flips)
        text[position(text.size() - 1)] ^= static_cast<char>(1 << std::uniform_int_distribution<int>(0, 7)(random));
      return text;
    case 4: // a line lost or repeated
    {
      const std::size_t begin = text.rfind('\n', position(text.size())) + 1; // (npos + 1 = 0)
      const std::size_t end = std::min(text.find('\n', begin), text.size() - 1) + 1;
      const std::string line = text.substr(begin, end - begin);
      return random() % 2 ? text.erase(begin, end - begin) : text.insert(begin, line);
    }
    default: // nothing of the file left
    {
      std::string garbage(position(256), '\0');
      for (char& c : garbage)
        c = static_cast<char>(std::uniform_int_distribution<int>(0, 255)(random));
      return garbage;
    }
  }
}

} // namespace testing
