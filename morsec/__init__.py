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
    if ctypes.util.find_library("EGL"):
        _os.environ["MUJOCO_GL"] = "egl"
    elif ctypes.util.find_library("OSMesa"):
        _os.environ["MUJOCO_GL"] = "osmesa"
        _os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")


_choose_gl()

__all__ = ["__version__"]
