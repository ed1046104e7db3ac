"""Run a builder script and hand its scene to the shared pipeline.

    morsec build mysim.py        load_scene -> run_builder_script -> validate_scene (same as YAML)
    python mysim.py [-- CMD ...] Environment.create() -> standalone_main -> `morsec CMD mysim.py ...`

Any problem is one line naming the script's file:line (exit 2, no traceback): a builder call that
cannot be recorded, a method that does not exist, an exception raised by the script itself.
"""

from __future__ import annotations

import builtins
import os
import sys
import traceback
from contextlib import contextmanager
from pathlib import Path

from pydantic import BaseModel

from morsec.component.catalogue import Catalogue, load_catalogue, use_source
from morsec.errors import MorsecError, SceneError, did_you_mean
from morsec.frontends.builder import builder_names
from morsec.frontends.builder import session as _session
from morsec.frontends.builder.session import BuilderAttributeError, Recording, Session, is_builder_file
from morsec.scene.validate import validate_scene

# recordings of scripts that ran as plain Python in this process (python mysim.py), by absolute path
_preloaded: dict[str, Recording] = {}


def run_builder_script(path: Path, catalogue: Catalogue | None = None, strict: bool = False) -> BaseModel:
    """The validated, resolved IR of a builder script (what load_scene gives for YAML). `strict`: a warning
    (a MORSE-only call, an unknown property kept as a tag) is an error instead (`morsec check --strict`)."""
    path = Path(path)
    cat = catalogue or load_catalogue(path.parent)
    recording = record_script(path, cat)
    if strict and recording.records:
        raise recording.strict_error()
    recording.report()
    return validate_scene(recording.data, recording.smap, cat)


def record_script(path: Path, catalogue: Catalogue | None = None) -> Recording:
    """Execute the script with the builder recording: the raw scene dict, its source map, the warnings."""
    path = Path(path)
    key = os.path.abspath(path)
    if key in _preloaded:
        return _preloaded.pop(key)
    try:
        source = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneError(f"{path}: no such builder script") from None
    except (OSError, UnicodeDecodeError) as err:
        raise SceneError(f"{path}: cannot read: {err}") from None
    try:
        code = compile(source, str(path), "exec", dont_inherit=True)
    except SyntaxError as err:
        raise SceneError(f"Python syntax error: {err.msg}", str(path), err.lineno, err.offset) from None
    cat = catalogue or load_catalogue(path.parent)
    session = Session(cat, path)
    namespace = {"__name__": "__main__", "__file__": str(path.resolve()), "__builtins__": builtins,
                 "__doc__": None, "__package__": None, "__spec__": None, "__loader__": None, "__cached__": None}
    with _running(session, path):
        try:
            exec(code, namespace)
        except MorsecError:
            raise
        except SystemExit as stop:
            if stop.code not in (None, 0):
                raise SceneError(f"the script exited with {stop.code!r}", *_script_position(stop, path)) from None
        except RecursionError as err:
            raise script_error(err, path) from None
        except Exception as err:
            raise script_error(err, path) from None
        session.end_of_script(namespace)
        return session.recording()


@contextmanager
def recording(catalogue: Catalogue | None = None, script: Path | None = None):
    """Record builder calls made from Python code (a notebook, a test) instead of a script file:

        with recording() as session:
            robot = ATRV(); robot.append(Pose()); env = Environment('empty')
        scene = validate_scene(*session.scene_data(), session.catalogue)

    `script`: the file making the calls (a test file), which errors and the source map then name.
    """
    session = Session(catalogue or load_catalogue(), script)
    _session.push(session)
    try:
        yield session
    finally:
        _session.pop(session)


@contextmanager
def _running(session: Session, path: Path):
    """The session is current (builder objects, from `morse.builder` or `morsec.builder`, record into it) and
    the script's folder is on sys.path."""
    saved_argv, saved_path = sys.argv, list(sys.path)
    sys.argv = [str(path)]
    sys.path.insert(0, str(path.resolve().parent))
    for source in session.catalogue.sources:  # a MORSE simulation's src/: its builder classes and components
        use_source(source)
    _session.push(session)
    try:
        yield
    finally:
        _session.pop(session)
        sys.argv = saved_argv
        sys.path[:] = saved_path


def _script_position(err: BaseException, path: Path) -> tuple[str, int | None, int | None]:
    """file, line, column of the innermost frame of the script (else of the innermost user frame)."""
    target = os.path.abspath(path)
    frames = traceback.extract_tb(err.__traceback__)
    chosen = None
    for frame in frames:
        if os.path.abspath(frame.filename) == target:
            chosen = frame
    if chosen is None:
        user = [f for f in frames if not is_builder_file(f.filename) and f.filename != __file__]
        chosen = user[-1] if user else None
    if chosen is None:
        return str(path), None, None
    col = (chosen.colno + 1) if getattr(chosen, "colno", None) is not None else None
    filename = str(path) if os.path.abspath(chosen.filename) == target else chosen.filename
    return filename, chosen.lineno, col


def script_error(err: BaseException, path: Path) -> SceneError:
    file, line, col = _script_position(err, path)
    if isinstance(err, BuilderAttributeError):
        message = str(err)
    elif isinstance(err, ModuleNotFoundError) and (err.name or "").split(".")[0] == "morse":
        message = (f"{type(err).__name__}: {err}: morsec's morse package has morse.builder, morse.testing and "
                   "the parts of morse.core and morse.helpers MORSE's components use (docs/coming-from-morse.md)")
    elif isinstance(err, ModuleNotFoundError) and (err.name or "").split(".")[0] in ("bpy", "bge", "mathutils"):
        message = f"{type(err).__name__}: {err}: morsec runs without Blender; its Python modules do not exist"
    else:
        text = str(err).strip().splitlines()
        message = f"{type(err).__name__}: {text[0]}" if text else type(err).__name__
        name = getattr(err, "name", None)
        if isinstance(err, NameError) and isinstance(name, str) and name[:1].isupper():
            message += (f"{did_you_mean(name, builder_names())} (no builder class of that name: "
                        "`morsec components` lists the catalogue)")
    return SceneError(message, file, line, col)


# ---------------------------------------------------------------- python mysim.py

def preload(script: Path, recording: Recording) -> None:
    """The recording of a script that ran as plain Python, handed to the pipeline instead of running it again."""
    _preloaded[os.path.abspath(script)] = recording
