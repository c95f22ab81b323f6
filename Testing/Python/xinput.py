"""The user's hand in the GUI tests: real mouse and key events through the X server's XTest
extension (libXtst, which Xvfb has), as a user's mouse and keyboard make them. They reach the
application through the window system's queue, at the moment they are sent, whatever the
application is doing then (e.g. in the middle of an update), unlike events posted inside Qt.
Each call returns once the X server has the events (XSync). The calls keep Python's lock (PyDLL)
and wait without letting it go (a busy wait), so that they can be made from a VTK observer that
runs inside an update the GUI's event processing started (ParaView's VTK calls Python there
without taking the lock for it)."""
import ctypes
import ctypes.util
import time

_x11 = ctypes.PyDLL(ctypes.util.find_library('X11') or 'libX11.so.6')
_xtst = ctypes.PyDLL(ctypes.util.find_library('Xtst') or 'libXtst.so.6')
_x11.XOpenDisplay.restype = ctypes.c_void_p
_x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
_x11.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]
_x11.XStringToKeysym.restype = ctypes.c_ulong
_x11.XStringToKeysym.argtypes = [ctypes.c_char_p]
_x11.XKeysymToKeycode.restype = ctypes.c_ubyte
_x11.XKeysymToKeycode.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
_xtst.XTestFakeMotionEvent.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_int, ctypes.c_ulong]
_xtst.XTestFakeButtonEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int, ctypes.c_ulong]
_xtst.XTestFakeKeyEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int, ctypes.c_ulong]

_display = _x11.XOpenDisplay(None)
if not _display:
    raise RuntimeError('xinput: cannot open the X display (DISPLAY not set?)')

# keysym names of the characters that are not their own name
_KEYSYMS = {' ': 'space', '.': 'period', '-': 'minus', '_': 'underscore', '/': 'slash', ',': 'comma', '*': 'asterisk'}


def wait(seconds):
    """Waits, holding Python's lock."""
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        pass


def _sync(seconds):
    _x11.XSync(_display, 0)
    wait(seconds)  # the application's connection reads them (Qt's reader thread)


def move(x, y, wait=0.0):
    """Moves the pointer to the global position (x, y) in pixels."""
    _xtst.XTestFakeMotionEvent(_display, -1, int(round(x)), int(round(y)), 0)
    _sync(wait)


def press(button=1, wait=0.0):
    _xtst.XTestFakeButtonEvent(_display, button, 1, 0)
    _sync(wait)


def release(button=1, wait=0.0):
    _xtst.XTestFakeButtonEvent(_display, button, 0, 0)
    _sync(wait)


def click(x, y, button=1, wait=0.0, modifiers=()):
    """A click at the global position (x, y), holding the modifier keys given by name ('Control_L')."""
    held = [_keycode(m) for m in modifiers]
    for code in held:
        _xtst.XTestFakeKeyEvent(_display, code, 1, 0)
    move(x, y)
    press(button)
    release(button)
    for code in reversed(held):
        _xtst.XTestFakeKeyEvent(_display, code, 0, 0)
    _sync(wait)


def _keycode(name):
    keysym = _x11.XStringToKeysym(name.encode())
    code = _x11.XKeysymToKeycode(_display, keysym)
    if not code:
        raise ValueError('xinput: no key for %r' % name)
    return code


def key(name, modifiers=(), wait=0.0):
    """Presses and releases a key by its keysym name ('a', 'Return', 'BackSpace'), holding the
    modifier keys given by name ('Control_L', 'Shift_L')."""
    held = [_keycode(m) for m in modifiers]
    for code in held:
        _xtst.XTestFakeKeyEvent(_display, code, 1, 0)
    code = _keycode(name)
    _xtst.XTestFakeKeyEvent(_display, code, 1, 0)
    _xtst.XTestFakeKeyEvent(_display, code, 0, 0)
    for code in reversed(held):
        _xtst.XTestFakeKeyEvent(_display, code, 0, 0)
    _sync(wait)


def type_text(text, wait=0.0):
    """Types lower-case letters, digits and the characters of _KEYSYMS."""
    for character in text:
        key(_KEYSYMS.get(character, character))
    _sync(wait)


def centre(widget):
    """The global position of a Qt widget's centre (PyQt5)."""
    point = widget.mapToGlobal(widget.rect().center())
    return point.x(), point.y()
