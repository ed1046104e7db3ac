"""`morsec render`: a picture of a scene from a camera, headless on the CPU (EGL, else OSMesa)."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np

from morsec.errors import MorsecError, RuntimeFailure
from morsec.kits.mjcf_names import DEFAULT_CAMERA


def open_renderer(model, width: int, height: int):
    """A mujoco.Renderer, or a one-line RuntimeFailure naming the system package that is missing."""
    import os

    import mujoco
    use_chosen_gl()
    max_w, max_h = int(model.vis.global_.offwidth), int(model.vis.global_.offheight)
    if width > max_w or height > max_h:
        raise MorsecError(f"image {width}x{height} is larger than the scene's offscreen buffer {max_w}x{max_h}")
    try:
        return mujoco.Renderer(model, height, width)
    except Exception as err:  # no GL at all, or a backend that cannot start
        backend = os.environ.get("MUJOCO_GL", "")
        package = {"egl": "libegl1 and libgl1-mesa-dri (Debian)", "osmesa": "libosmesa6 (Debian)"}.get(
            backend, "libegl1 or libosmesa6 (Debian)")
        raise RuntimeFailure(f"cannot render with MUJOCO_GL={backend or '(unset)'}: {err}; install {package} "
                             "or set MUJOCO_GL=osmesa") from None


HEADLESS_GL = ("egl", "osmesa")  # the backends morsec chooses (morsec/__init__.py) and can install late


def use_chosen_gl() -> None:
    """MuJoCo reads MUJOCO_GL once, when it is first imported: a program (or a test session) that imported
    mujoco before morsec got MuJoCo's default, GLFW, which needs a display. Hand mujoco.Renderer the
    headless backend morsec chose (EGL or OSMesa, in MUJOCO_GL) instead."""
    import os
    try:
        from mujoco.rendering.classic import gl_context
    except ImportError:
        return
    wanted = os.environ.get("MUJOCO_GL", "").lower().strip()
    chosen = getattr(gl_context, "_MUJOCO_GL", wanted)
    if chosen == wanted or wanted not in HEADLESS_GL:
        return
    try:
        _install_gl(gl_context, wanted)
    except ImportError:
        return  # open_renderer reports what is missing


def import_mujoco_gl_on_first_use() -> None:
    """Import MuJoCo without its GL backend, and have the backend morsec chose (MUJOCO_GL: egl or osmesa)
    imported when something first renders (mujoco.Renderer, or anything asking for `GLContext`). EGL's
    import (PyOpenGL, libEGL) is a tenth of a start and 4 MiB that a run without cameras never uses.
    MuJoCo imported already, or another MUJOCO_GL: nothing changes. Child processes see MUJOCO_GL as it was."""
    import os
    import sys
    wanted = os.environ.get("MUJOCO_GL", "").lower().strip()
    if "mujoco" in sys.modules or wanted not in HEADLESS_GL:
        return
    original = os.environ["MUJOCO_GL"]
    os.environ["MUJOCO_GL"] = "disable"
    try:
        import mujoco
        from mujoco.rendering.classic import gl_context
    finally:
        os.environ["MUJOCO_GL"] = original

    _answer_gl_context(gl_context, gl_context, wanted)  # mujoco.Renderer's way to its backend
    _answer_gl_context(mujoco, gl_context, wanted)  # mujoco.GLContext, as an eager import has it


def _answer_gl_context(module, gl_context, backend: str) -> None:
    """Have `module` answer `GLContext`, which it lacks, by installing `backend` (PEP 562: a module's
    __getattr__ answers the names its namespace lacks)."""
    def missing(name: str):
        if name != "GLContext":
            raise AttributeError(f"module {module.__name__!r} has no attribute {name!r}")
        return _install_gl(gl_context, backend)

    module.__getattr__ = missing


def _install_gl(gl_context, backend: str):
    """mujoco's GLContext for `backend` (egl or osmesa), set where mujoco.Renderer looks for it; ImportError
    (as MuJoCo's own placeholder raises it) when the backend cannot be loaded."""
    try:
        if backend == "egl":
            from mujoco.egl import GLContext
        else:
            from mujoco.osmesa import GLContext
    except (ImportError, OSError, RuntimeError) as err:
        raise ImportError(f"Failed to import OpenGL backend (MUJOCO_GL={backend!r}): {err}") from err
    gl_context.GLContext = GLContext
    gl_context._MUJOCO_GL = backend
    return GLContext


def render_build(build_dir: Path, out: Path, camera: str | None = None, width: int = 800, height: int = 600) -> Path:
    """A PNG of the build's scene, drawn as its display settings say (morsec.kits.display); the settings a
    picture cannot show are named in one warning."""
    import mujoco

    from morsec.kits import display
    manifest = json.loads((Path(build_dir) / "manifest.json").read_text())
    model = mujoco.MjModel.from_xml_path(str(Path(build_dir) / "scene.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    name = camera or DEFAULT_CAMERA
    if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, name) < 0:
        cameras = [model.camera(i).name for i in range(model.ncam)]
        raise MorsecError(f"no camera {name!r} in the scene; cameras: {', '.join(cameras)}")
    environment = manifest["scene"]["environment"]
    if (line := display.warning(environment, display.RENDER)) is not None:
        logging.getLogger("morsec.display").warning(line)
    look = display.look(environment)
    renderer = open_renderer(model, width, height)
    try:
        renderer.update_scene(data, camera=name, scene_option=look.option)
        for flag, value in look.flags.items():
            renderer.scene.flags[flag] = value
        renderer.scene.stereo = look.stereo
        image = renderer.render()
    finally:
        renderer.close()
    from morsec.kits.png import write_png
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    write_png(out, np.asarray(image))
    return out
