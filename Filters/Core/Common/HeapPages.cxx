#include "Common/HeapPages.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mlsdeform
{
std::size_t populateHeap(double fraction)
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
      // the lower part, whole pages: malloc hands the reserve out from its low end
      const unsigned long length = static_cast<unsigned long>(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(end - begin)) & ~4095ul;
      // pages already present stay as they are; one that is not gets a zero page, as malloc expects of fresh heap
      if (length == 0 || madvise(reinterpret_cast<void*>(begin), length, MADV_POPULATE_WRITE) == 0)
      {
        size = length;
      }
      break;
    }
  }
  std::fclose(maps);
  return size;
#else
  (void)fraction;
  return 0;
#endif
}
} // namespace mlsdeform
