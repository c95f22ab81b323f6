#pragma once

#include <cstddef>

namespace mlsdeform
{
/// Faults in the lower `fraction` of the process's heap (the main malloc arena's region, "[heap]"
/// in /proc/self/maps; whole pages), writable, without changing what it holds: the pages malloc has
/// reserved but not handed out yet (it hands them out from the low end) are touched now, not by the
/// allocation that gets them later. Where a page's first touch is dear (a virtual machine whose
/// host takes back the memory its guest frees: virtio-balloon free page reporting, 1.6-1.9 s per
/// GiB in huge pages here) a thread that would sit idle pays it instead of the critical path. The
/// reserve is large only with the batch allocator's top_pad (mlsdeform/allocator.py: 256 MiB); with
/// glibc's defaults this touches almost nothing. Returns the bytes populated, 0 where there is no
/// heap or the kernel cannot populate (Linux before 5.14, other systems).
std::size_t populateHeap(double fraction = 1.0);
} // namespace mlsdeform
