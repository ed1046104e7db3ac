"""A key pressed in this process's own X11 windows (XSendEvent to the windows whose _NET_WM_PID is ours):
how morsec asks mujoco.viewer's window for what its Python API lacks (full screen: its F5 key).
libX11 through ctypes; no effect, and False, where there is no X11 display (Wayland alone, macOS)."""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import time

KEY_PRESS, KEY_RELEASE = 2, 3
KEY_PRESS_MASK, KEY_RELEASE_MASK = 1, 2
XA_CARDINAL = 6
SEARCH_DEPTH = 3  # a window manager puts a client window one or two levels below the root


class _XKeyEvent(ctypes.Structure):
    _fields_ = [("type", ctypes.c_int), ("serial", ctypes.c_ulong), ("send_event", ctypes.c_int),
                ("display", ctypes.c_void_p), ("window", ctypes.c_ulong), ("root", ctypes.c_ulong),
                ("subwindow", ctypes.c_ulong), ("time", ctypes.c_ulong), ("x", ctypes.c_int), ("y", ctypes.c_int),
                ("x_root", ctypes.c_int), ("y_root", ctypes.c_int), ("state", ctypes.c_uint),
                ("keycode", ctypes.c_uint), ("same_screen", ctypes.c_int),
                ("pad", ctypes.c_long * 16)]  # XEvent is a union of 24 longs


def _xlib():
    path = ctypes.util.find_library("X11")
    if path is None:
        return None
    x = ctypes.CDLL(path)
    p, win, ulong = ctypes.c_void_p, ctypes.c_ulong, ctypes.c_ulong
    x.XOpenDisplay.restype, x.XOpenDisplay.argtypes = p, [ctypes.c_char_p]
    x.XCloseDisplay.argtypes = [p]
    x.XFlush.argtypes = [p]
    x.XFree.argtypes = [p]
    x.XDefaultRootWindow.restype, x.XDefaultRootWindow.argtypes = win, [p]
    x.XInternAtom.restype, x.XInternAtom.argtypes = ulong, [p, ctypes.c_char_p, ctypes.c_int]
    x.XQueryTree.argtypes = [p, win, ctypes.POINTER(win), ctypes.POINTER(win),
                             ctypes.POINTER(ctypes.POINTER(win)), ctypes.POINTER(ctypes.c_uint)]
    x.XGetWindowProperty.argtypes = [p, win, ulong, ctypes.c_long, ctypes.c_long, ctypes.c_int, ulong,
                                     ctypes.POINTER(ulong), ctypes.POINTER(ctypes.c_int), ctypes.POINTER(ulong),
                                     ctypes.POINTER(ulong), ctypes.POINTER(p)]
    x.XKeysymToKeycode.restype, x.XKeysymToKeycode.argtypes = ctypes.c_ubyte, [p, ulong]
    x.XSendEvent.argtypes = [p, win, ctypes.c_int, ctypes.c_long, p]
    return x


def press_in_own_windows(keysym: int, timeout: float = 5.0, pid: int | None = None) -> bool:
    """Press and release `keysym` in each window of this process (or of process `pid`), waiting up to
    `timeout` s for one to exist; False when there is no X11 display or no such window."""
    x = _xlib() if os.environ.get("DISPLAY") else None
    if x is None:
        return False
    display = x.XOpenDisplay(None)
    if not display:
        return False
    try:
        root = x.XDefaultRootWindow(display)
        end = time.monotonic() + timeout
        while not (windows := _windows_of(pid or os.getpid(), x, display, root)):
            if time.monotonic() > end:
                return False
            time.sleep(0.05)
        keycode = x.XKeysymToKeycode(display, keysym)
        for window in windows:
            for kind, mask in ((KEY_PRESS, KEY_PRESS_MASK), (KEY_RELEASE, KEY_RELEASE_MASK)):
                event = _XKeyEvent(type=kind, send_event=1, display=display, window=window, root=root,
                                   keycode=keycode, same_screen=1)
                x.XSendEvent(display, window, 1, mask, ctypes.byref(event))
        x.XFlush(display)
        return True
    finally:
        x.XCloseDisplay(display)


def _windows_of(pid: int, x, display, root: int) -> list[int]:
    pid_atom = x.XInternAtom(display, b"_NET_WM_PID", 0)
    found, level = [], [root]
    for _ in range(SEARCH_DEPTH):
        level = [child for window in level for child in _children(x, display, window)]
        found += [window for window in level if _pid(x, display, window, pid_atom) == pid]
    return found


def _children(x, display, window: int) -> list[int]:
    root, parent, kids, count = ctypes.c_ulong(), ctypes.c_ulong(), ctypes.POINTER(ctypes.c_ulong)(), ctypes.c_uint()
    if not x.XQueryTree(display, window, ctypes.byref(root), ctypes.byref(parent), ctypes.byref(kids),
                        ctypes.byref(count)):
        return []
    children = [kids[i] for i in range(count.value)]
    if kids:
        x.XFree(kids)
    return children


def _pid(x, display, window: int, atom: int) -> int | None:
    kind, fmt, count, after, data = (ctypes.c_ulong(), ctypes.c_int(), ctypes.c_ulong(), ctypes.c_ulong(),
                                     ctypes.c_void_p())
    if x.XGetWindowProperty(display, window, atom, 0, 1, 0, XA_CARDINAL, ctypes.byref(kind), ctypes.byref(fmt),
                            ctypes.byref(count), ctypes.byref(after), ctypes.byref(data)) != 0 or not data.value:
        return None
    try:
        return int(ctypes.cast(data, ctypes.POINTER(ctypes.c_ulong))[0]) if count.value else None
    finally:
        x.XFree(data)
