"""Issue 57 point 3: every command in README.md and in the gallery (Examples/README.md) is copied
from something a test runs. A command is a line (with its continuations) of an indented block that
starts with a program; the tests cited in its section (`Python.X`, `Examples.X`: registered in this
build) must run it: every word of it (its programs, scripts, options and their values) is in the
cited test's command line or in a file of the project that command line names (and the project's
modules those files import). What a reader chooses is left out: folders under /tmp and out/, the
plugin's path (tests use the build's), and xvfb-run with its options (the tests' own X server
stands in for it). The quick start's two commands are checked against what runs them: .ci/run (the
test command) and Examples.DeformFandisk.Python (the main job's deformation).

  python3 test_readme_commands.py SOURCE_DIR BUILD_DIR
"""
import json
import os
import re
import shlex
import subprocess
import sys

from checks import check, finish

source, build = sys.argv[1:3]
PROGRAMS = ('bash', 'pvpython', 'pvbatch', 'python3', 'paraview', 'xvfb-run', 'mpiexec', 'mkdir', 'build/', '(cd',
            'OMP_NUM_THREADS=')
QUICK_START = {'bash Examples/run-demo.sh': 'Examples.DeformFandisk.Python', 'bash Testing/run-tests.sh': None}

tests = {t['name']: ' '.join(t.get('command', [])) for t in json.loads(subprocess.run(
    ['ctest', '--show-only=json-v1'], cwd=build, capture_output=True, text=True, check=True).stdout)['tests']}


def project_file(token):
    """The project's file a command-line token names, or None."""
    token = token.strip('\'"')
    return token if token.startswith(source) and os.path.isfile(token) else None


def test_text(name):
    """A test's command line and the project's files it names, with the modules they import."""
    text = tests[name]
    files = [f for f in map(project_file, re.split(r"[\s=;&|]+", text)) if f]
    seen = set()
    while files:
        path = files.pop()
        if path in seen:
            continue
        seen.add(path)
        content = open(path, errors='replace').read()
        text += '\n' + content
        for module in re.findall(r'^\s*(?:from|import)\s+([A-Za-z_][A-Za-z0-9_]*)', content, re.M):
            for folder in ('Examples', 'Examples/OpenFOAM', 'Examples/Structural', 'Testing/Python'):
                candidate = os.path.join(source, folder, module + '.py')
                if os.path.isfile(candidate):
                    files.append(candidate)
    return text


def words(command):
    """The words of a command a test must run: programs, script names, options and values."""
    tokens = shlex.split(command.replace('\\\n', ' '), posix=True)
    kept, skip = [], 0
    for i, token in enumerate(tokens):
        if skip:
            skip -= 1
            continue
        if token == 'xvfb-run':
            while i + 1 < len(tokens) and tokens[i + 1].startswith('-'):
                skip += 2 if tokens[i + 1] == '-s' else 1
                i += 2 if tokens[i + 1] == '-s' else 1
            continue
        token = token.strip('()')
        if token in ('&&', '|', ';', '') or token.startswith('/tmp') or token.startswith('out/') or token == 'out':
            continue
        if 'plugins/MLSDeform' in token:
            option = token.split('=', 1)[0] + '=' if token.startswith('--') and '=' in token else None
            if option:
                kept.append(option)
            continue
        if '/' in token:
            token = os.path.basename(token.rstrip('/'))
        kept.append(token)
    return kept


def commands(path):
    """(section, command) for every command of the file's indented blocks."""
    lines = open(path).read().split('\n')
    section, out, fenced, previous_blank = '', [], False, True
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith('```'):
            fenced = not fenced
        elif not fenced and line.startswith('#'):
            section = line
        elif not fenced and previous_blank and re.match(r'^ {4,}\S', line):
            # an indented block: its commands
            while i < len(lines) and (re.match(r'^ {4,}\S', lines[i]) or lines[i].strip() == ''):
                text = lines[i].strip()
                while text.endswith('\\') and i + 1 < len(lines):
                    i += 1
                    text = text[:-1] + ' ' + lines[i].strip()
                if text.startswith(PROGRAMS):
                    out.append((section, text))
                i += 1
            previous_blank = True
            continue
        previous_blank = line.strip() == ''
        i += 1
    return out


def sections(path):
    """The text of each section (heading to heading) of the file."""
    found, section = {}, ''
    fenced = False
    for line in open(path).read().split('\n'):
        if line.startswith('```'):
            fenced = not fenced
        if not fenced and line.startswith('#'):
            section = line
        found[section] = found.get(section, '') + line + '\n'
    return found


for document in ('README.md', 'Examples/README.md'):
    path = os.path.join(source, document)
    texts = sections(path)
    found = commands(path)
    check(len(found) >= 5, '%s: %d commands found' % (document, len(found)))
    for section, command in found:
        if command in QUICK_START:
            runner = QUICK_START[command]
            if runner is None:
                ok = command in open(os.path.join(source, '.ci', 'run')).read()
            else:
                demo = open(os.path.join(source, 'Examples', 'run-demo.sh')).read()
                script = re.search(r'pvbatch "\$root/Examples/([^"]+)"', demo).group(1)
                ok = runner in tests and script in tests[runner]
            check(ok, '%s: the quick start\'s "%s" is what %s runs' % (document, command, runner or '.ci/run'))
            continue
        cited = [name for name in re.findall(r'`([A-Za-z0-9_.]+)`', texts[section]) if name in tests]
        missing = {}
        for name in cited:
            text = test_text(name)
            missing[name] = [w for w in words(command) if w not in text]
        ok = any(not m for m in missing.values())
        check(ok, '%s (%s): "%s" is run by %s' % (document, section.strip('# '), command,
                                                  [n for n, m in missing.items() if not m] if ok else
                                                  'none of the cited tests %s (words missing: %s)' % (cited, missing)))
finish()
