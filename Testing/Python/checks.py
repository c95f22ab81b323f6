"""The Python tests' checks: each prints ok or FAIL with what it checked; finish() exits non-zero
when any failed, write_result() reports them from a script run inside the paraview GUI."""
import sys

failures = []


def check(condition, what):
    print(('ok   ' if condition else 'FAIL ') + what, flush=True)
    if not condition:
        failures.append(what)


def raises(call, text, what):
    """call raises a ValueError whose message contains text."""
    try:
        call()
    except ValueError as e:
        check(text in str(e), '%s: %s' % (what, e))
        return
    check(False, '%s raises ValueError' % what)


def finish():
    if failures:
        sys.exit('%d check(s) failed: %s' % (len(failures), '; '.join(failures)))
    print('all checks passed')


def write_result(path, error=None):
    """For a script inside the paraview GUI, which swallows exceptions and exit codes: writes 'ok',
    or the failures and the error, to the file the test reads."""
    lines = failures + (['error: %s' % error] if error else [])
    with open(path, 'w') as f:
        f.write(('\n'.join(lines) if lines else 'ok') + '\n')


def settle(app, until=lambda: False, seconds=10.0):
    """For a script inside the paraview GUI: lets the Qt application's panel and Auto Apply timers
    run, until the condition holds or the time is up."""
    import time
    end = time.time() + seconds
    while True:
        for _ in range(20):
            app.processEvents()
        if until() or time.time() > end:
            return
        time.sleep(0.02)
