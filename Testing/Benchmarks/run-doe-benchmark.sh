#!/usr/bin/env bash
# Variants per hour: a design of experiments on the hull case (issue 30, point 5) against moveMesh
# producing the same variants.
#
# On the cached "DTC hull in a box" case (run-openfoam-benchmark.sh builds it), a Latin hypercube
# of --samples variants (default 50, seed 0) over three design variables of the hull (dx: -0.2 to
# 0.2 m, yaw: -3 to 3 degrees, sx: the length scale, -5% to 5%), inlet and outlet fixed, sides,
# bottom and top slipping, as the command line mlsdeform-doe.py runs it in Debian's python3 (a plain
# VTK pipeline; mlsdeform.designOfExperiments: deform, quality verdict, a linked variant case
# written: openfoam/doe_benchmark.py), with OMP_NUM_THREADS 1 and 2 (--threads).
# Then --movemesh variants (default 3) by moveMesh (displacementLaplacian from the hull's
# prescribed displacement, the same map, on a copy of the case each), timed one by one: moveMesh's
# batch time is their median times the number of variants (an extrapolation, as the table says);
# between them MLS Deform's first variant again in a process of its own per thread count, so that
# the first variant's ratio is a median of --movemesh runs against a median of as many; and
# moveMesh's first once more with the batch allocator's glibc tunables (mlsdeform/allocator.py).
# Prints the machine (CPU model, cores per socket, threads per core; what fresh memory costs), then per thread count: the
# share of CPU time the hypervisor gave to other guests during the run (steal), the same first
# variant in pvpython on paraview.simple proxies (openfoam/first_variant.py), the whole batch's
# wall time (process start to the last variant), variants per hour, seconds per
# variant (first, median), disk per variant against the points file's size, peak RSS; moveMesh's
# seconds per variant and disk; the targets (10,000 variants per hour on 2 threads, 5,000 on 1;
# the first variant within 0.6x moveMesh's; a variant's own bytes within 1.2x its points file)
# met or not; and a JSON line (DOEBENCHMARK ...).
#
# Usage: Testing/Benchmarks/run-doe-benchmark.sh [--cells small|400k|1M] [--samples N] [--movemesh K] [--threads "1 2"]
# Environment: MLSDEFORM_BUILD, MLSDEFORM_PLUGIN, MLSDEFORM_BENCHMARK_DIR as run-openfoam-benchmark.sh.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here=$root/Testing/Benchmarks/openfoam
size=1M
samples=50
movemesh=3
threads="1 2"
while (($#)); do
  case "$1" in
    --cells) size=${2:?--cells small|400k|1M}; shift 2 ;;
    --samples) samples=${2:?--samples N}; shift 2 ;;
    --movemesh) movemesh=${2:?--movemesh K}; shift 2 ;;
    --threads) threads=${2:?--threads LIST}; shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown argument $1 (--cells small|400k|1M, --samples N, --movemesh K, --threads LIST)" >&2; exit 2 ;;
  esac
done
build=${MLSDEFORM_BUILD:-$root/build}
plugin=${MLSDEFORM_PLUGIN:-$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so}
work=${MLSDEFORM_BENCHMARK_DIR:-$build/openfoam-benchmark}
[ -f "$plugin" ] || bash "$root/Testing/setup.sh"
[ -x /usr/bin/time ] || { echo "/usr/bin/time is needed (Debian package time)" >&2; exit 1; }
mkdir -p "$work"
work=$(cd "$work" && pwd)
case=$(bash "$here/cached-hull-case.sh" "$size" "$work")
set +u
source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1
set -u
run=$work/doe-$size
rm -rf "$run"
mkdir -p "$run"
cp -r "$(dirname "$plugin")" "$run/plugin"   # a rebuild during the runs does not mix builds
plugin_path=$run/plugin${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}

echo "Machine: $(lscpu | sed -n 's/^Model name: *//p'); $(nproc) CPUs; $(lscpu | sed -n 's/^Core(s) per socket: */cores per socket /p'), $(lscpu | sed -n 's/^Thread(s) per core: */threads per core /p')"
# the BLAS CHOLMOD's solves and factorization run on (Debian's alternatives: OpenBLAS or the reference BLAS)
# what makes fresh memory cheap or dear on this machine (mlsdeform/allocator.py): transparent huge
# pages (the batch allocator asks for them by madvise) and the kernel's page-table isolation
echo "Transparent huge pages: $(cat /sys/kernel/mm/transparent_hugepage/enabled 2>/dev/null || echo unknown); page-table isolation: $(cat /sys/devices/system/cpu/vulnerabilities/meltdown 2>/dev/null || echo unknown)"
# and what it costs: 256 MiB of fresh memory touched once per 4 KiB page, with and without huge
# pages, and then (huge pages) memory this process freed just before. Where the host takes back
# what its guest frees (virtio-balloon free page reporting: the guest reports free 2 MiB blocks
# after about 2 s), every process's first touch pays the host's fault, and memory reused at once
# does not: a batch that keeps its memory (mlsdeform/allocator.py) pays it once.
reporting=unknown
for features in /sys/bus/virtio/drivers/virtio_balloon/virtio*/features; do
  [ -r "$features" ] && reporting=$([ "$(cut -c6 "$features")" = 1 ] && echo on || echo off)   # VIRTIO_BALLOON_F_REPORTING, bit 5
done
[ "$reporting" = unknown ] && reporting="no virtio balloon"
echo "Free page reporting to the host (virtio-balloon): $reporting"
/usr/bin/python3 - << 'PROBE'
import mmap, time
size = 256 << 20
figures = []
for huge, label in ((False, ''), (True, ' with huge pages'), (True, ' with huge pages, freed just before')):
    if 'freed' not in label:
        time.sleep(3)  # by then the host has taken back what the block before freed, as between two processes
    block = mmap.mmap(-1, size, flags=mmap.MAP_PRIVATE | mmap.MAP_ANONYMOUS)
    if huge:
        block.madvise(mmap.MADV_HUGEPAGE)
    began = time.perf_counter()
    for offset in range(0, size, 4096):
        block[offset] = 1
    seconds = time.perf_counter() - began
    figures.append('%.2f us per 4 KiB page (%.2f s per GiB)%s' % (seconds / (size / 4096) * 1e6, seconds * (1 << 30) / size, label))
    block.close()
print('Fresh memory, first touch: ' + '; '.join(figures))
PROBE
# whether each CPU runs at full speed now, alone and with the other busy: a guest's virtual CPU may
# be one hardware thread of a physical core whose other thread the host gives to other work, which
# lscpu does not show and which is not counted as steal. A compute kernel (arithmetic on a 512 KiB
# array, within the core's caches) and a memory kernel (copies of 128 MiB, past the caches), in a
# process pinned to each CPU alone, then in two at once, the best of 3 each. An OpenMP loop split
# evenly takes as long as its slowest thread: a CPU at half speed makes 2 threads no faster than 1.
/usr/bin/python3 - << 'PROBE'
import multiprocessing, os, time
import numpy as np


def compute():
    x = np.ones(1 << 16)
    began = time.perf_counter()
    for _ in range(60000):
        np.multiply(x, 0.999, out=x)
        np.add(x, 0.001, out=x)
    return time.perf_counter() - began


def memory():
    source, target = np.ones(16 << 20), np.zeros(16 << 20)   # first touched before the clock starts
    began = time.perf_counter()
    for _ in range(16):
        np.copyto(target, source)
    return time.perf_counter() - began


def on(cpus, kernel):
    """The kernel's seconds in one process pinned to each of cpus, started at once."""
    fork = multiprocessing.get_context('fork')
    results = fork.Queue()

    def run(cpu):
        os.sched_setaffinity(0, {cpu})
        results.put((cpu, kernel()))

    processes = [fork.Process(target=run, args=(cpu,)) for cpu in cpus]
    for process in processes:
        process.start()
    seconds = dict(results.get() for _ in processes)
    for process in processes:
        process.join()
    return [seconds[cpu] for cpu in cpus]


cpus = sorted(os.sched_getaffinity(0))[:2]
for kernel, name in ((compute, 'compute'), (memory, 'memory')):
    alone = [min(on([cpu], kernel)[0] for _ in range(3)) for cpu in cpus]
    both = [min(s) for s in zip(*(on(cpus, kernel) for _ in range(3)))]
    print('CPU speed, %s kernel [s]: alone %s; both at once %s' % (
        name, ', '.join('CPU %d %.2f' % c for c in zip(cpus, alone)), ', '.join('CPU %d %.2f' % c for c in zip(cpus, both))))
PROBE
echo "BLAS: $(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3), LAPACK: $(readlink -f /usr/lib/x86_64-linux-gnu/liblapack.so.3)"
echo "Case: $(grep -E '^ *cells:' "$case/log.checkMesh" | tr -s ' ') $(grep -E '^ *points:' "$case/log.checkMesh" | tr -s ' '); $samples variants"
# the machine's CPU time so far: all of it and the part the hypervisor gave to other guests
# (steal): a virtual machine whose CPUs are shared runs slower by that much, which no setting here changes
cpu_times() { awk '/^cpu /{ total = 0; for (i = 2; i <= NF; i++) total += $i; print total, $9 }' /proc/stat; }
for t in $threads; do
  echo "MLS Deform, OMP_NUM_THREADS=$t (load $(cut -d' ' -f1-3 /proc/loadavg))"
  read -r total0 steal0 < <(cpu_times)
  OMP_NUM_THREADS=$t LD_LIBRARY_PATH=$plugin_path /usr/bin/time -v -o "$run/mls-$t.time" \
    /usr/bin/python3 "$here/doe_benchmark.py" "$run/plugin" "$case/case.foam" "$run/mls-$t" "$samples" "$movemesh" \
    > "$run/mls-$t.log" 2>&1 || { tail -30 "$run/mls-$t.log"; exit 1; }
  tail -1 "$run/mls-$t.log" | grep -v DOEBENCH || true
  read -r total1 steal1 < <(cpu_times)
  # the same first variant in pvpython on paraview.simple proxies (ParaView's server manager)
  mkdir -p "$run/pv-$t"
  OMP_NUM_THREADS=$t LD_LIBRARY_PATH=$plugin_path /usr/bin/time -v -o "$run/pv-$t.time" \
    pvpython --no-mpi "$here/first_variant.py" "$run/plugin" "$case/case.foam" "$run/pv-$t" > "$run/pv-$t.log" 2>&1 || { tail -30 "$run/pv-$t.log"; exit 1; }
  awk -v t=$((total1 - total0)) -v s=$((steal1 - steal0)) 'BEGIN { printf "%.1f\n", (t > 0 ? 100 * s / t : 0) }' > "$run/steal-$t"
done

first=$(set -- $threads; echo "$1")
# moveMesh on a copy of the case with variant I's hull displacement, timed into NAME.time (its
# output in NAME.log); the copy stays in $run/NAME. Environment GLIBC_TUNABLES passes through.
move_mesh() {
  local i=$1 name=$2 copy=$run/$2
  mkdir -p "$copy"
  cp -r "$case/0" "$case/constant" "$case/system" "$copy/"
  cp "$run/mls-$first/pointDisplacement-$i" "$copy/0/pointDisplacement"
  (cd "$copy" && /usr/bin/time -v -o "$run/$name.time" moveMesh > "$run/$name.log" 2>&1) ||
    { tail -30 "$run/$name.log"; exit 1; }
}
for ((i = 0; i < movemesh; i++)); do
  echo "moveMesh variant $((i + 1))/$movemesh (load $(cut -d' ' -f1-3 /proc/loadavg))"
  move_mesh "$i" "moveMesh-$i"
  (cd "$run/moveMesh-$i" && checkMesh -latestTime > "$run/checkMesh.moveMesh-$i" 2>&1) || true
  du -sb "$run/moveMesh-$i" | cut -f1 > "$run/moveMesh-$i.bytes"
  # between moveMesh's runs, MLS Deform's first variant once more per thread count (a process that
  # makes one variant), so that both sides' medians come from the same stretch of time
  if ((i + 1 < movemesh)); then
    for t in $threads; do
      echo "MLS Deform's first variant again, OMP_NUM_THREADS=$t (load $(cut -d' ' -f1-3 /proc/loadavg))"
      OMP_NUM_THREADS=$t LD_LIBRARY_PATH=$plugin_path \
        /usr/bin/python3 "$here/doe_benchmark.py" "$run/plugin" "$case/case.foam" "$run/first-$t-$i" 1 0 \
        > "$run/first-$t-$i.log" 2>&1 || { tail -30 "$run/first-$t-$i.log"; exit 1; }
      rm -rf "$run/first-$t-$i"
    done
  fi
done
# moveMesh once more on the first variant, started with the batch allocator's glibc tunables
# (mlsdeform/allocator.py): what the same setting gives OpenFOAM on this machine
if ((movemesh > 0)); then
  echo "moveMesh variant 1 with the batch allocator's tunables (load $(cut -d' ' -f1-3 /proc/loadavg))"
  GLIBC_TUNABLES=$(python3 "$run/plugin/mlsdeform/allocator.py") move_mesh 0 moveMesh-tuned
  rm -rf "$run/moveMesh-tuned"
fi
python3 "$here/doe_report.py" "$run" "$threads" "$movemesh"
