"""A virtual X display (Xvfb) for the viewer tests, and screenshots of its windows read
with libX11 (``XQueryTree`` / ``XGetWindowAttributes`` / ``XGetImage`` through ctypes)."""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import shutil
import signal
import subprocess
import time

import numpy as np

XVFB_MISSING = (
    "Xvfb is missing: the viewer tests open windows on a virtual display; install it "
    "(Debian/Ubuntu: apt-get install xvfb; python/scripts/test.sh does this when run as root or with sudo)"
)


def _die_with_parent() -> None:
    """In the child: SIGTERM when the process that started it ends (Linux's PR_SET_PDEATHSIG)."""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


def start_xvfb(width: int = 1600, height: int = 1200) -> str:
    """Starts Xvfb on a free display number (``-displayfd``) for the rest of this process:
    it ends when the process does, after the windows' libraries (GLFW, Qt), which end the
    process (or crash) when their display goes away under them. Returns ``":N"``.

    Raises:
        RuntimeError: when Xvfb is missing (saying what to install) or does not start.
    """
    exe = shutil.which("Xvfb")
    if exe is None:
        raise RuntimeError(XVFB_MISSING)
    read, write = os.pipe()
    proc = subprocess.Popen(
        [exe, "-displayfd", str(write), "-screen", "0", f"{width}x{height}x24", "-nolisten", "tcp"],
        pass_fds=(write,),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        preexec_fn=_die_with_parent,
    )
    os.close(write)
    with os.fdopen(read) as f:
        number = f.readline().strip()
    if not number:
        raise RuntimeError(f"Xvfb exited with {proc.wait(5)} before naming its display")
    return f":{number}"


class _XWindowAttributes(ctypes.Structure):
    _fields_ = [
        ("x", ctypes.c_int), ("y", ctypes.c_int), ("width", ctypes.c_int), ("height", ctypes.c_int),
        ("border_width", ctypes.c_int), ("depth", ctypes.c_int), ("visual", ctypes.c_void_p),
        ("root", ctypes.c_ulong), ("class", ctypes.c_int), ("bit_gravity", ctypes.c_int),
        ("win_gravity", ctypes.c_int), ("backing_store", ctypes.c_int), ("backing_planes", ctypes.c_ulong),
        ("backing_pixel", ctypes.c_ulong), ("save_under", ctypes.c_int), ("colormap", ctypes.c_ulong),
        ("map_installed", ctypes.c_int), ("map_state", ctypes.c_int), ("all_event_masks", ctypes.c_long),
        ("your_event_mask", ctypes.c_long), ("do_not_propagate_mask", ctypes.c_long),
        ("override_redirect", ctypes.c_int), ("screen", ctypes.c_void_p),
    ]


class _XImage(ctypes.Structure):
    _fields_ = [
        ("width", ctypes.c_int), ("height", ctypes.c_int), ("xoffset", ctypes.c_int), ("format", ctypes.c_int),
        ("data", ctypes.c_void_p), ("byte_order", ctypes.c_int), ("bitmap_unit", ctypes.c_int),
        ("bitmap_bit_order", ctypes.c_int), ("bitmap_pad", ctypes.c_int), ("depth", ctypes.c_int),
        ("bytes_per_line", ctypes.c_int), ("bits_per_pixel", ctypes.c_int),
    ]


def _x11() -> ctypes.CDLL:
    lib = ctypes.CDLL(ctypes.util.find_library("X11") or "libX11.so.6")
    lib.XOpenDisplay.restype = ctypes.c_void_p
    lib.XOpenDisplay.argtypes = [ctypes.c_char_p]
    lib.XDefaultRootWindow.restype = ctypes.c_ulong
    lib.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
    lib.XQueryTree.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.POINTER(ctypes.c_ulong),
                               ctypes.POINTER(ctypes.c_ulong), ctypes.POINTER(ctypes.POINTER(ctypes.c_ulong)),
                               ctypes.POINTER(ctypes.c_uint)]
    lib.XGetWindowAttributes.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.POINTER(_XWindowAttributes)]
    lib.XGetImage.restype = ctypes.POINTER(_XImage)
    lib.XGetImage.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int, ctypes.c_uint,
                              ctypes.c_uint, ctypes.c_ulong, ctypes.c_int]
    lib.XFree.argtypes = [ctypes.c_void_p]
    lib.XCloseDisplay.argtypes = [ctypes.c_void_p]
    return lib


def windows(display: str) -> list[tuple[int, int, int, int]]:
    """The mapped top-level windows of ``display`` as ``(x, y, width, height)``."""
    x = _x11()
    dpy = x.XOpenDisplay(display.encode())
    if not dpy:
        raise RuntimeError(f"cannot open display {display}")
    try:
        root = x.XDefaultRootWindow(dpy)
        r, p = ctypes.c_ulong(), ctypes.c_ulong()
        children = ctypes.POINTER(ctypes.c_ulong)()
        n = ctypes.c_uint()
        x.XQueryTree(dpy, root, ctypes.byref(r), ctypes.byref(p), ctypes.byref(children), ctypes.byref(n))
        out = []
        for i in range(n.value):
            attrs = _XWindowAttributes()
            x.XGetWindowAttributes(dpy, children[i], ctypes.byref(attrs))
            if attrs.map_state == 2 and attrs.width > 16 and attrs.height > 16:  # IsViewable
                out.append((attrs.x, attrs.y, attrs.width, attrs.height))
        if children:
            x.XFree(children)
        return out
    finally:
        x.XCloseDisplay(dpy)


def screenshot(display: str, box: tuple[int, int, int, int]) -> np.ndarray:
    """The screen's pixels in ``box`` = ``(x, y, width, height)``: RGB uint8, top row first."""
    x = _x11()
    dpy = x.XOpenDisplay(display.encode())
    if not dpy:
        raise RuntimeError(f"cannot open display {display}")
    try:
        left, top, w, h = box
        image = x.XGetImage(dpy, x.XDefaultRootWindow(dpy), left, top, w, h, 0xFFFFFFFF, 2)  # ZPixmap
        if not image:
            raise RuntimeError(f"XGetImage failed for {box}")
        img = image.contents
        assert img.bits_per_pixel == 32, img.bits_per_pixel
        raw = ctypes.string_at(img.data, img.bytes_per_line * img.height)
        pixels = np.frombuffer(raw, np.uint8).reshape(img.height, img.bytes_per_line // 4, 4)[:, :w]
        rgb = pixels[..., [2, 1, 0]].copy()  # BGRX, little endian
        x.XFree(ctypes.c_void_p(img.data))
        x.XFree(image)
        return rgb
    finally:
        x.XCloseDisplay(dpy)


def wait_for(predicate, timeout: float = 20.0, every: float = 0.1):  # type: ignore[no-untyped-def]
    """Polls ``predicate()`` until it returns something truthy (returned) or ``timeout``
    seconds pass (then returns the last value)."""
    end = time.monotonic() + timeout
    value = predicate()
    while not value and time.monotonic() < end:
        time.sleep(every)
        value = predicate()
    return value
