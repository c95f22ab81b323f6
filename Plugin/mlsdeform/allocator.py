"""The memory allocator of a batch process (the command line mlsdeform-doe.py, the benchmarks).

A 1M-cell variant allocates and frees arrays of tens of MB at every step: the reader's and the
set-up's arrays, each variant's points, quality figures and written file. glibc's defaults give
such blocks their own fresh memory (mmap) and return them when freed, so every one of them is
faulted in again page by page (4 KiB). On some virtual machines a page's first touch is dear: on a
2-CPU AMD EPYC guest whose virtio balloon reports free memory to the host (which takes it back
about 2 s after the guest freed it) it took 11-21 us per 4 KiB page, where an ordinary machine
takes well under 1 us (run-doe-benchmark.sh prints both), and the 1M-cell hull case's
set-up took 11.0 s and a further variant 0.99 s with glibc's defaults, 7.5-8.0 s and 0.46 s with
the tunables below. moveMesh, one process per variant, pays the first touch once per run, as the
set-up does; a batch with glibc's defaults pays it again at every variant. The tunables keep freed
memory for reuse and back the heap with transparent huge pages (2 MiB, where
/sys/kernel/mm/transparent_hugepage/enabled allows madvise). The answer does not depend on them.

glibc reads its tunables at the process's start only, so restartWithBatchAllocator() executes the
process again, the same command, with them in GLIBC_TUNABLES; call it first, before the package
(which loads VTK) is imported. A long-lived process (ParaView's GUI, pvpython) can be started with
GLIBC_TUNABLES set as batchTunables() gives it, and keeps the freed memory for reuse then too.

This module imports nothing of the package, so that a script can run it by its path first
(runpy.run_path), as mlsdeform-doe.py does.
"""
import os
import sys

# glibc 2.35+ malloc tunables (the same for every batch process), with why each:
TUNABLES = (
    # madvise(MADV_HUGEPAGE) on the heap and on mmap'ed blocks: one fault per 2 MiB, not per 4 KiB
    ('glibc.malloc.hugetlb', '1'),
    # blocks up to 32 MiB (glibc's largest threshold; a 1M-point coordinate array is 28.6 MiB) come
    # from the heap and are reused after free, not unmapped
    ('glibc.malloc.mmap_threshold', str(32 << 20)),
    # the heap's freed top is kept, not given back and faulted in again at the next variant
    ('glibc.malloc.trim_threshold', str((1 << 32) - 1)),
    # the heap grows by 256 MiB at a time (address space only; pages are faulted in when used, or
    # ahead by the thread that reads an OpenFOAM case's faces while VTK's reader runs:
    # Core/Common/HeapPages.h)
    ('glibc.malloc.top_pad', str(256 << 20)),
)


def batchTunables(current=None):
    """GLIBC_TUNABLES with TUNABLES added to ``current`` (default: this process's); a tunable
    already set there keeps its value."""
    current = os.environ.get('GLIBC_TUNABLES', '') if current is None else current
    entries = [e for e in current.split(':') if e]
    named = {e.split('=', 1)[0] for e in entries}
    return ':'.join(entries + ['%s=%s' % (name, value) for name, value in TUNABLES if name not in named])


def restartWithBatchAllocator():
    """Executes this process again, the same command line, with batchTunables() in GLIBC_TUNABLES;
    returns without doing anything where they are already set, where the interpreter is not a
    plain python (pvpython and pvbatch have started MPI by then), under an MPI launcher, or on a
    system without /proc."""
    tunables = batchTunables()
    if tunables == os.environ.get('GLIBC_TUNABLES', ''):
        return
    executable = os.path.realpath(sys.executable or '')
    if not os.path.basename(executable).startswith('python') or any(
            key in os.environ for key in ('OMPI_COMM_WORLD_SIZE', 'PMI_SIZE', 'PMIX_RANK', 'MPI_LOCALNRANKS')):
        return
    try:
        if os.path.realpath('/proc/self/exe') != executable:
            return
        with open('/proc/self/cmdline', 'rb') as f:
            argv = [a.decode(errors='surrogateescape') for a in f.read().split(b'\0')[:-1]]
    except OSError:
        return
    sys.stdout.flush()
    sys.stderr.flush()
    os.execve(executable, argv, dict(os.environ, GLIBC_TUNABLES=tunables))


if __name__ == '__main__':
    # GLIBC_TUNABLES for a process started by hand: GLIBC_TUNABLES=$(python3 .../mlsdeform/allocator.py) pvpython ...
    print(batchTunables())
