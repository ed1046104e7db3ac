"""morsec: MORSE scenes compiled to MuJoCo."""

import os as _os
import sys as _sys

__version__ = "0.1.0"


def _choose_gl() -> None:
    """Headless OpenGL for MuJoCo's offscreen renderer, chosen before MuJoCo is imported (it reads
    MUJOCO_GL once): EGL (Mesa on the CPU) when libEGL is there, else OSMesa. A user's MUJOCO_GL wins."""
    if "MUJOCO_GL" in _os.environ or not _sys.platform.startswith("linux"):
        return
    import ctypes.util
    if _loads("libEGL.so.1") or ctypes.util.find_library("EGL"):  # find_library runs ldconfig: tried second
        _os.environ["MUJOCO_GL"] = "egl"
    elif ctypes.util.find_library("OSMesa"):
        _os.environ["MUJOCO_GL"] = "osmesa"
        _os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")


def _loads(soname: str) -> bool:
    """Whether the dynamic loader finds `soname` (loaded as MuJoCo's GL binding would load it)."""
    import ctypes
    try:
        ctypes.CDLL(soname)
    except OSError:
        return False
    return True


_choose_gl()

__all__ = ["__version__"]
