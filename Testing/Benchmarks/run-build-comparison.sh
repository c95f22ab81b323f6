#!/usr/bin/env bash
# Two builds timed side by side on the design of experiments (issue 64, point 3: a guard against
# the next regression). This build's plugin and the plugin built from a given commit (the last
# release, origin/main, a commit before a change) run the DOE benchmark's batch
# (openfoam/doe_benchmark.py: the hull case, a Latin hypercube over dx, yaw and sx, each variant
# deformed, given its quality verdict and written) on each case size, one process per run, the two
# builds alternating run by run, so that both meet the same machine. Prints per case and phase
# (set-up, deform, verdict, write, the first variant, a further variant) the medians over the runs
# of both builds and their ratio (this build over the other), and one JSON line (BUILDCOMPARISON).
#
# The other build is made once in the build folder (baseline-<commit>/, a git worktree of the
# commit and its build: about 15 minutes on 2 cores) and kept for later runs. Both plugin folders
# are copied first, so that a rebuild during the runs does not mix builds. The other build's own
# Python layer (its plugin folder's mlsdeform) runs its batch; this build's doe_benchmark.py drives
# both.
#
# Usage: Testing/Benchmarks/run-build-comparison.sh COMMIT [--cells "small 400k"] [--samples 10] [--runs 3] [--threads 2]
# Environment: MLSDEFORM_BUILD (this build, default build/), MLSDEFORM_BENCHMARK_DIR (the cases, as
# run-openfoam-benchmark.sh).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
here=$root/Testing/Benchmarks/openfoam
ref=
cells="small 400k"
samples=10
runs=3
threads=2
while (($#)); do
  case "$1" in
    --cells) cells=${2:?--cells LIST}; shift 2 ;;
    --samples) samples=${2:?--samples N}; shift 2 ;;
    --runs) runs=${2:?--runs N}; shift 2 ;;
    --threads) threads=${2:?--threads N}; shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "unknown option $1 (--cells LIST, --samples N, --runs N, --threads N)" >&2; exit 2 ;;
    *) ref=$1; shift ;;
  esac
done
[ -n "$ref" ] || { echo "usage: run-build-comparison.sh COMMIT [--cells LIST] [--samples N] [--runs N] [--threads N]" >&2; exit 2; }
commit=$(git -C "$root" rev-parse --verify "$ref^{commit}") || { echo "no commit $ref in $root" >&2; exit 2; }
build=${MLSDEFORM_BUILD:-$root/build}
plugin=$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so
[ -f "$plugin" ] || bash "$root/Testing/setup.sh"
work=${MLSDEFORM_BENCHMARK_DIR:-$build/openfoam-benchmark}
mkdir -p "$work"
work=$(cd "$work" && pwd)

# the other build, made once
baseline=$build/baseline-${commit:0:12}
other=$baseline/build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so
# the plugin and its Python wrapping (which the DOE's python3 imports)
if [ ! -f "$other" ] || [ ! -f "$(dirname "$other")/mlsdeform_wrapping/MLSDeformFilters.so" ]; then
  echo "Building $ref (${commit:0:12}) in $baseline (once; about 15 minutes on 2 cores)"
  [ -d "$baseline/src" ] || git -C "$root" worktree add --detach "$baseline/src" "$commit" > /dev/null
  cmake -S "$baseline/src" -B "$baseline/build" -DCMAKE_BUILD_TYPE=Release > "$baseline/configure.log" 2>&1 ||
    { tail -20 "$baseline/configure.log"; exit 1; }
  cmake --build "$baseline/build" -j "$(nproc)" --target MLSDeform MLSDeformFiltersPython MLSDeformReadersPython > "$baseline/build.log" 2>&1 ||
    { tail -30 "$baseline/build.log"; exit 1; }
fi

out=$work/build-comparison
rm -rf "$out"
mkdir -p "$out"
cp -r "$(dirname "$plugin")" "$out/plugin-this"
cp -r "$(dirname "$other")" "$out/plugin-other"
set +u
source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1
set -u
echo "This build: $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- Filters Readers Plugin || echo ' (with changes)'); the other: ${commit:0:12} ($ref)"
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) CPUs; OMP_NUM_THREADS=$threads; $samples variants a run, $runs runs a build"
for size in $cells; do
  case=$(bash "$here/cached-hull-case.sh" "$size" "$work")
  for r in $(seq 1 "$runs"); do
    for b in other this; do
      folder=$out/$size-$b-$r
      OMP_NUM_THREADS=$threads LD_LIBRARY_PATH=$out/plugin-$b${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH} \
        /usr/bin/python3 "$here/doe_benchmark.py" "$out/plugin-$b" "$case/case.foam" "$folder" "$samples" 0 > "$folder.log" 2>&1 ||
        { tail -20 "$folder.log"; exit 1; }
      grep '^DOEBENCH ' "$folder.log" | tail -1 | sed 's/^DOEBENCH //' > "$folder.json"
      rm -rf "$folder" # the variants: 28 MB each on the 1M case
    done
  done
done
/usr/bin/python3 - "$out" "$cells" "$runs" << 'REPORT'
import json
import statistics
import sys

out, cells, runs = sys.argv[1], sys.argv[2].split(), int(sys.argv[3])
phases = [('set-up [s]', lambda d: d['setup_s']),
          ('deform, a further variant [s]', lambda d: d['parts_s']['deform_s']),
          ('verdict [s]', lambda d: d['parts_s']['quality_s']),
          ('write [s]', lambda d: d['parts_s']['write_s']),
          ('first variant after the set-up [s]', lambda d: d['variant_s']['first']),
          ('further variant, median [s]', lambda d: d['variant_s']['median'])]
result = {}
print('\n%-38s %10s %10s %8s' % ('', 'other', 'this', 'ratio'))
for size in cells:
    runs_of = {b: [json.load(open('%s/%s-%s-%d.json' % (out, size, b, r))) for r in range(1, runs + 1)] for b in ('other', 'this')}
    print('%s case' % size)
    result[size] = {}
    for name, value in phases:
        other = statistics.median(value(d) for d in runs_of['other'])
        this = statistics.median(value(d) for d in runs_of['this'])
        ratio = this / other if other > 0 else float('nan')
        result[size][name] = {'other': other, 'this': this, 'ratio': ratio}
        print('  %-36s %10.3f %10.3f %7.2fx' % (name, other, this, ratio))
print('BUILDCOMPARISON ' + json.dumps(result))
REPORT
