#include "Common/HeapPages.h"

#include <cstdio>
#include <cstring>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mlsdeform
{
std::size_t populateHeap()
{
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  std::FILE* maps = std::fopen("/proc/self/maps", "r");
  if (!maps)
  {
    return 0;
  }
  std::size_t size = 0;
  char line[4096];
  while (std::fgets(line, sizeof line, maps))
  {
    unsigned long begin = 0, end = 0;
    if (std::strstr(line, "[heap]") && std::sscanf(line, "%lx-%lx", &begin, &end) == 2 && end > begin)
    {
      // pages already present stay as they are; a page that is not gets a zero page, as malloc expects of fresh heap
      if (madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE) == 0)
      {
        size = end - begin;
      }
      break;
    }
  }
  std::fclose(maps);
  return size;
#else
  return 0;
#endif
}
} // namespace mlsdeform
