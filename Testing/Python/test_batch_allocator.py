"""The batch allocator (mlsdeform/allocator.py beside the plugin), as mlsdeform-doe.py runs it first:
a python3 process is executed again once, with the same arguments and glibc's batch tunables in
GLIBC_TUNABLES; a tunable the user set keeps its value; a process under an MPI launcher or in
pvpython is left alone; glibc takes the settings (a touched 64 MiB block lies on transparent huge
pages where the kernel allows them by madvise); the command line still runs.
Usage: python3 test_batch_allocator.py PLUGIN_FILE PVPYTHON"""
import json
import os
import subprocess
import sys

plugin, pvpython = sys.argv[1:3]
folder = os.path.dirname(os.path.abspath(plugin))
allocator = os.path.join(folder, 'mlsdeform', 'allocator.py')
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

# a child that says what it is before and after the restart, then touches a 64 MiB block
child = r'''
import json, os, runpy, sys
print(json.dumps({"pid": os.getpid(), "tunables": os.environ.get("GLIBC_TUNABLES"), "argv": sys.argv[1:]}), flush=True)
runpy.run_path(%r)["restartWithBatchAllocator"]()
print(json.dumps({"after": os.getpid(), "tunables": os.environ.get("GLIBC_TUNABLES")}), flush=True)
if "--touch" in sys.argv:
    import ctypes
    libc = ctypes.CDLL(None)
    libc.malloc.restype = ctypes.c_void_p
    size = 64 << 20
    block = libc.malloc(size)
    ctypes.memset(block, 1, size)
    huge = sum(int(line.split()[1]) for line in open("/proc/self/smaps_rollup") if line.startswith("AnonHugePages:"))
    print(json.dumps({"huge_kib": huge}), flush=True)
''' % allocator
script = os.path.join(os.environ.get('TMPDIR', '/tmp'), 'mlsdeform-allocator-child-%d.py' % os.getpid())
with open(script, 'w') as f:
    f.write(child)


def run(interpreter, arguments, env=None):
    environment = {k: v for k, v in os.environ.items() if k != 'GLIBC_TUNABLES'}
    environment.update(env or {})
    result = subprocess.run([interpreter, script] + arguments, capture_output=True, text=True, env=environment)
    lines = [json.loads(line) for line in result.stdout.splitlines() if line.startswith('{')]
    return result, lines


expected = subprocess.run([sys.executable, allocator], capture_output=True, text=True, check=True).stdout.strip()
names = [entry.split('=')[0] for entry in expected.split(':')]
check(set(names) == {'glibc.malloc.hugetlb', 'glibc.malloc.mmap_threshold', 'glibc.malloc.trim_threshold', 'glibc.malloc.top_pad'},
      'allocator.py prints the four batch tunables (%s)' % expected)

# python3: one restart, same process, same arguments, the tunables set
result, lines = run(sys.executable, ['a b', '--touch'])
check(result.returncode == 0, 'the restarted child exits with 0 (%s)' % result.stderr[-500:])
check(len(lines) == 4 and lines[0]['tunables'] is None and lines[1]['tunables'] == expected,
      'the child ran twice: first without, then with the tunables (%s)' % lines[:2])
check(len(lines) == 4 and lines[0]['pid'] == lines[1]['pid'] == lines[2]['after'],
      'the restart is an exec of the same process, once')
check(len(lines) == 4 and lines[0]['argv'] == lines[1]['argv'] == ['a b', '--touch'], 'the arguments are kept, spaces included')
thp = open('/sys/kernel/mm/transparent_hugepage/enabled').read() if os.path.exists('/sys/kernel/mm/transparent_hugepage/enabled') else ''
if '[never]' in thp or not thp:
    print('huge pages not checked: transparent huge pages are off on this kernel (%s)' % thp.strip())
else:
    # glibc.malloc.hugetlb=1 advises huge pages for the block: at least one 2 MiB page of the 64 MiB
    check(len(lines) == 4 and lines[3]['huge_kib'] >= 2048, 'glibc took the tunables: the touched block has huge pages (%s)' % lines[3:])
    _, plain = run(sys.executable, ['--touch'], {'GLIBC_TUNABLES': 'glibc.malloc.hugetlb=0'})
    check(len(lines) == 4 and plain and plain[-1].get('huge_kib', 1 << 30) < lines[3]['huge_kib'],
          "with the user's hugetlb=0 kept, fewer huge pages (%s)" % plain[-1:])

# a tunable the user set keeps its value; the others are added
result, lines = run(sys.executable, [], {'GLIBC_TUNABLES': 'glibc.malloc.hugetlb=0:glibc.malloc.arena_max=2'})
check(len(lines) == 3 and lines[1]['tunables'].startswith('glibc.malloc.hugetlb=0:glibc.malloc.arena_max=2:') and
      all(n in lines[1]['tunables'] for n in names), "the user's settings come first and stay (%s)" % lines[1:2])

# already set: no restart
result, lines = run(sys.executable, [], {'GLIBC_TUNABLES': expected})
check(len(lines) == 2 and lines[0]['tunables'] == expected, 'with the tunables already set, no restart (%s)' % lines)

# under an MPI launcher (its processes have started MPI's wiring) and in pvpython: left alone
result, lines = run(sys.executable, [], {'PMI_SIZE': '2'})
check(len(lines) == 2 and lines[1]['tunables'] is None, 'under an MPI launcher, no restart (%s)' % lines)
result, lines = run(pvpython, [])
check(result.returncode == 0 and len(lines) == 2 and lines[1]['tunables'] is None,
      'in pvpython, no restart (%s %s)' % (lines, result.stderr[-300:]))

# the command line restarts itself and still runs (its usage error: exit code 2 and the message)
command = subprocess.run([sys.executable, os.path.join(folder, 'mlsdeform-doe.py')], capture_output=True, text=True,
                         env={k: v for k, v in os.environ.items() if k != 'GLIBC_TUNABLES'})
check(command.returncode == 2 and 'usage: mlsdeform-doe.py' in command.stderr, 'mlsdeform-doe.py without arguments: usage, exit 2')
os.remove(script)
finish()
