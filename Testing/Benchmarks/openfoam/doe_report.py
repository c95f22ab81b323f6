"""The design-of-experiments benchmark's table (run-doe-benchmark.sh): MLS Deform's batches (one per
thread count) beside moveMesh's timed variants, against issue 64's targets (variants per hour by
thread count, the first variant within 0.6x moveMesh) and issue 30's (disk, memory).
Usage: python3 doe_report.py RUN_FOLDER "THREADS" MOVEMESH"""
import json
import os
import re
import statistics
import sys

run, threads, movemesh = sys.argv[1], sys.argv[2].split(), int(sys.argv[3])
TARGET_PER_HOUR, TARGET_DISK = {'1': 5000, '2': 10000}, 1.2  # per thread count; more threads: the 2 threads' target


def elapsed(path):
    """Wall time and peak RSS (MiB) from /usr/bin/time -v."""
    text = open(path).read()
    clock = re.search(r'Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)', text)
    seconds = int(clock.group(1) or 0) * 3600 + int(clock.group(2)) * 60 + float(clock.group(3))
    return seconds, int(re.search(r'Maximum resident set size \(kbytes\): (\d+)', text).group(1)) / 1024


def first_variant_s(r):
    """The first variant's seconds: the process's start-up, the set-up (read included), the variant."""
    return r['startup_s'] + r['setup_s'] + r['variant_s']['first']


figures = {'threads': {}}
for t in threads:
    line = next(l for l in open('%s/mls-%s.log' % (run, t)) if l.startswith('DOEBENCH '))
    r = json.loads(line[len('DOEBENCH '):])
    wall, rss = elapsed('%s/mls-%s.time' % (run, t))
    n = r['samples']
    # the batch: from the process's start to its last variant written (the timed parts and the
    # moveMesh inputs that doe_benchmark.py makes after it are not the batch's)
    r.update(wall_s=wall, rss_mib=rss, per_hour=3600 * n / r['process_s'], steady_per_hour=3600 / r['variant_s']['median'],
             disk_ratio=r['disk_per_variant_bytes'] / r['points_file_bytes'] if r['points_file_bytes'] else float('nan'))
    r['steal_percent'] = float(open('%s/steal-%s' % (run, t)).read())
    pv_line = next(l for l in open('%s/pv-%s.log' % (run, t)) if l.startswith('FIRSTVARIANT '))
    r['pv'] = json.loads(pv_line[len('FIRSTVARIANT '):])
    r['pv']['rss_mib'] = elapsed('%s/pv-%s.time' % (run, t))[1]
    # the first variant: the batch's, then the runs of one variant between moveMesh's runs
    again = [json.loads(next(l for l in open('%s/first-%s-%d.log' % (run, t, i), encoding='utf-8') if l.startswith('DOEBENCH '))
                        [len('DOEBENCH '):]) for i in range(movemesh - 1)]
    r['first_runs_s'] = [first_variant_s(x) for x in [r] + again]
    r['first_s'] = statistics.median(r['first_runs_s'])
    figures['threads'][t] = r
moves = [elapsed('%s/moveMesh-%d.time' % (run, i)) for i in range(movemesh)]
mm = statistics.median(m[0] for m in moves) if moves else float('nan')
mm_bytes = statistics.median(int(open('%s/moveMesh-%d.bytes' % (run, i)).read()) for i in range(movemesh)) if moves else 0
figures['moveMesh'] = {'seconds': [m[0] for m in moves], 'median_s': mm, 'rss_mib': max((m[1] for m in moves), default=0),
                       'disk_bytes': mm_bytes}

print('\n%-34s %s' % ('', ''.join('%20s' % ('MLS Deform, %s thr' % t) for t in threads)) + '%20s' % 'moveMesh')
n = figures['threads'][threads[0]]['samples']


def row(label, values, moveMesh=''):
    print('%-34s %s%20s' % (label, ''.join('%20s' % v for v in values), moveMesh))


T = [figures['threads'][t] for t in threads]


row('batch of %d variants [s]' % n, ['%.1f' % r['process_s'] for r in T], '%.1f (%d x median)' % (n * mm, n))
row('  (process start to the last write)', [''] * len(T), '')
row('variants per hour', ['%.0f' % r['per_hour'] for r in T], '%.0f' % (3600 / mm))
row('  after the set-up (median)', ['%.0f' % r['steady_per_hour'] for r in T], '')
row('first variant: process start to', [''] * len(T), '')
row('  its write [s] (python3 start-up,', ['%.2f' % r['first_s'] for r in T], '%.2f' % mm)
row('  read, set-up, deform, verdict)', ['%.2fx' % (r['first_s'] / mm) for r in T], '')
row('  median of %d runs [s]' % len(T[0]['first_runs_s']), [', '.join('%.1f' % x for x in r['first_runs_s']) for r in T],
    ', '.join('%.1f' % x for x in figures['moveMesh']['seconds']))
row('the same in pvpython (paraview.simple', ['%.2f' % r['pv']['first_s'] for r in T], '')
row('  proxies, mlsdeform.foam) [s]', ['%.2fx' % (r['pv']['first_s'] / mm) for r in T], '')
row('  its peak RSS [MiB]', ['%.0f: %.2fx' % (r['pv']['rss_mib'], r['pv']['rss_mib'] / figures['moveMesh']['rss_mib'])
                            if figures['moveMesh']['rss_mib'] else '%.0f' % r['pv']['rss_mib'] for r in T], '')
row('further variant, median [s]', ['%.2f' % r['variant_s']['median'] for r in T], '%.2f' % mm)
row('  of it: deform (its solve) [s]', ['%.2f (%.2f)' % (r['parts_s']['deform_s'], r['parts_s']['solve_s']) for r in T], '')
row('  quality verdict, write [s]', ['%.2f, %.2f' % (r['parts_s']['quality_s'], r['parts_s']['write_s']) for r in T], '')
row('disk per variant [MB]', ['%.1f' % (r['disk_per_variant_bytes'] / 1e6) for r in T], '%.1f' % (mm_bytes / 1e6))
row('  / points file', ['%.3f' % r['disk_ratio'] for r in T], '')
row('peak RSS [MiB]', ['%.0f' % r['rss_mib'] for r in T], '%.0f' % figures['moveMesh']['rss_mib'])
row('  / moveMesh', ['%.2fx' % (r['rss_mib'] / figures['moveMesh']['rss_mib']) for r in T], '')
row('CPU time stolen by the hypervisor', ['%.1f%%' % r['steal_percent'] for r in T], '')
row('variants passing the thresholds', ['%d/%d' % (r['ok'], n) for r in T], '')
print('\nmoveMesh: %d variants timed (%s s), the batch extrapolated from their median.' % (
    movemesh, ', '.join('%.1f' % s for s in figures['moveMesh']['seconds'])))
tuned = '%s/moveMesh-tuned.time' % run
if os.path.exists(tuned):
    seconds, rss = elapsed(tuned)
    figures['moveMesh']['tuned'] = {'seconds': seconds, 'rss_mib': rss}
    print("moveMesh with the batch allocator's tunables (variant 1): %.1f s, %.0f MiB; the first variant against it: %s" % (
        seconds, rss, ', '.join('%.2fx (%s thr)' % (r['first_s'] / seconds, t)
                                for t, r in zip(threads, T))))
for t, r in zip(threads, T):
    first = r['first_s'] / mm
    memory = r['rss_mib'] / figures['moveMesh']['rss_mib']
    per_hour = TARGET_PER_HOUR.get(t, TARGET_PER_HOUR['2'])
    print('targets, %s thread(s): %d variants/hour (target %d: %s); a variant %.2fx its points file (target <= %.1f: %s); '
          'the first variant %.2fx moveMesh (target <= 0.6: %s); memory %.2fx moveMesh (target <= 1.5: %s)' % (
              t, r['per_hour'], per_hour, 'met' if r['per_hour'] >= per_hour else 'NOT met', r['disk_ratio'],
              TARGET_DISK, 'met' if r['disk_ratio'] <= TARGET_DISK else 'NOT met', first, 'met' if first <= 0.6 else 'NOT met',
              memory, 'met' if memory <= 1.5 else 'NOT met'))
print('DOEBENCHMARK ' + json.dumps(figures))
