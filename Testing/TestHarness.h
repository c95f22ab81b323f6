// A minimal test harness: each test is a named function; the executable runs the one named on
// its command line (CTest registers one test per name). A failed CHECK prints and fails the test.
// "--count N" fails unless exactly N tests are registered: CMake passes the number of TEST( lines
// it found, so that a test it missed fails loudly instead of never running.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>

namespace testing
{
inline int& failures()
{
  static int count = 0;
  return count;
}
inline std::map<std::string, std::function<void()>>& registry()
{
  static std::map<std::string, std::function<void()>> tests;
  return tests;
}
struct Register
{
  Register(const char* name, std::function<void()> f) { registry()[name] = std::move(f); }
};
inline void listTests()
{
  for (const auto& entry : registry())
  {
    std::printf("  %s\n", entry.first.c_str());
  }
}
inline int run(int argc, char* argv[])
{
  if (argc == 3 && std::strcmp(argv[1], "--count") == 0)
  {
    const std::size_t expected = std::strtoul(argv[2], nullptr, 10);
    std::printf("%zu tests registered, CMake found %zu (TEST( at the start of a line):\n", registry().size(), expected);
    listTests();
    return registry().size() == expected ? 0 : 1;
  }
  if (argc < 2 || !registry().count(argv[1]))
  {
    std::printf("usage: %s TEST | --count N\ntests:\n", argv[0]);
    listTests();
    return 2;
  }
  registry()[argv[1]]();
  std::printf("%s: %s\n", argv[1], failures() ? "FAILED" : "passed");
  return failures() ? 1 : 0;
}
}

#define TEST(name)                                                                                 \
  static void name();                                                                              \
  static testing::Register register_##name(#name, name);                                          \
  static void name()

#define CHECK(condition)                                                                           \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::printf("%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition);                    \
      ++testing::failures();                                                                       \
    }                                                                                              \
  } while (0)

// |a - b| <= tolerance, printing both values when it fails.
#define CHECK_NEAR(a, b, tolerance)                                                                \
  do                                                                                               \
  {                                                                                                \
    const double va = (a), vb = (b), vt = (tolerance);                                             \
    if (!(std::abs(va - vb) <= vt))                                                                \
    {                                                                                              \
      std::printf("%s:%d: CHECK_NEAR failed: %s = %.17g, %s = %.17g, tolerance %g\n", __FILE__,   \
        __LINE__, #a, va, #b, vb, vt);                                                             \
      ++testing::failures();                                                                       \
    }                                                                                              \
  } while (0)

#define CHECK_THROWS(statement, Exception)                                                         \
  do                                                                                               \
  {                                                                                                \
    bool thrown = false;                                                                           \
    try                                                                                            \
    {                                                                                              \
      statement;                                                                                   \
    }                                                                                              \
    catch (const Exception& e)                                                                     \
    {                                                                                              \
      thrown = true;                                                                               \
      std::printf("expected error: %s\n", e.what());                                               \
    }                                                                                              \
    if (!thrown)                                                                                   \
    {                                                                                              \
      std::printf("%s:%d: %s did not throw %s\n", __FILE__, __LINE__, #statement, #Exception);     \
      ++testing::failures();                                                                       \
    }                                                                                              \
  } while (0)

#define TEST_MAIN                                                                                  \
  int main(int argc, char* argv[]) { return testing::run(argc, argv); }

// A test program that also writes the file its tests read, for tests in other languages:
// `PROGRAM --write PATH` calls write(PATH) and exits.
#define TEST_MAIN_WRITING(write)                                                                   \
  int main(int argc, char* argv[])                                                                 \
  {                                                                                                \
    if (argc == 3 && std::string(argv[1]) == "--write")                                            \
    {                                                                                              \
      write(argv[2]);                                                                              \
      return 0;                                                                                    \
    }                                                                                              \
    return testing::run(argc, argv);                                                               \
  }
