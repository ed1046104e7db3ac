"""One run of a builder script: the objects it created, in order, and the raw scene they describe.

Builder objects only record; `Session.scene_data()` turns the record into the plain dict a YAML scene
would give (plus a SourceMap pointing each entry at the script line that wrote it), and the shared
pipeline (`validate_scene`) does all checking. Names follow MORSE: an explicit `name` wins, else the
script variable the object was bound to (found by looking at the script's frames, as MORSE's
`close_context` / `_rename_components` do), and names taken twice among siblings get `_001`, `_002` ...
"""

from __future__ import annotations

import inspect
import os
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from morsec.component.catalogue import Catalogue, load_catalogue
from morsec.constants import DUPLICATE_SUFFIX, SEPARATOR
from morsec.errors import SceneError
from morsec.scene.sourcemap import SourceMap

_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))

Position = tuple[str | None, int | None, int | None]


class BuilderError(SceneError):
    """A builder call that cannot be recorded (unknown component, bad argument); names the script line."""


class BuilderAttributeError(AttributeError):
    """A call to a method or attribute that the builder object does not have."""


def is_builder_file(filename: str) -> bool:
    return os.path.dirname(os.path.abspath(filename)) == _PACKAGE_DIR


# ---------------------------------------------------------------- the current session

_stack: list[Session] = []
_standalone: Session | None = None


def current(create: bool = True) -> Session | None:
    """The session recording now: the one `morsec` opened for a script, or (plain `python script.py`)
    a standalone one made on first use."""
    global _standalone
    if _stack:
        return _stack[-1]
    if _standalone is None and create:
        main = sys.modules.get("__main__")
        main_file = getattr(main, "__file__", None)
        script = Path(main_file) if main_file else None
        folder = script.parent if script else Path.cwd()
        # `python mysim.py` builds at create(); elsewhere (a console, a notebook) the session only records
        runs_a_script = script is not None and script.suffix == ".py"
        _standalone = Session(load_catalogue(folder), script, standalone=runs_a_script)
    return _standalone


# what `python mysim.py` does at create(): set by the public `morsec.builder` (it hands the scene to the CLI)
_standalone_handler: Callable[[Session], None] | None = None


def on_standalone_create(handler: Callable[[Session], None]) -> None:
    global _standalone_handler
    _standalone_handler = handler


def finish_standalone(session: Session) -> None:
    if _standalone_handler is None:
        sys.stderr.write("error: this script ran as plain Python without `morsec.builder`; "
                         "use `morsec build SCRIPT` or `from morsec.builder import *`\n")
        raise SystemExit(2)
    _standalone_handler(session)


def recording_now() -> bool:
    """Whether morsec is recording builder calls now (a script under `morsec build/run`, `recording()`),
    as opposed to builder calls made by a plain-Python script on its own."""
    return bool(_stack)


def push(session: Session) -> None:
    _stack.append(session)


def pop(session: Session) -> None:
    if _stack and _stack[-1] is session:
        _stack.pop()


def current_catalogue() -> Catalogue:
    session = current(create=True)
    return session.catalogue


# ---------------------------------------------------------------- the session

@dataclass(frozen=True)
class ScriptWarning:
    """A warning about a script line: where, and what."""

    file: str | None
    line: int | None
    column: int | None
    message: str

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}:{self.column or 1}: " if self.file and self.line else (
            f"{self.file}: " if self.file else "")
        return f"{where}warning: {self.message}"


@dataclass
class Recording:
    """What a script said: the raw scene dict, where each entry was written, and the warnings."""

    data: dict
    smap: SourceMap
    records: list[ScriptWarning] = field(default_factory=list)

    @property
    def warnings(self) -> list[str]:
        return [str(w) for w in self.records]

    def report(self, stream=None) -> None:
        stream = stream or sys.stderr
        for line in self.warnings:
            stream.write(line + "\n")
        stream.flush()

    def strict_error(self) -> SceneError | None:
        """`morsec check --strict`: the first warning as an error (one line, its file:line:col), or None."""
        if not self.records:
            return None
        first = self.records[0]
        more = len(self.records) - 1
        tail = f"; {more} more warning{'s' if more > 1 else ''}" if more else ""
        return SceneError(f"{first.message} (--strict: warnings are errors{tail})", first.file, first.line,
                          first.column)


class Session:
    def __init__(self, catalogue: Catalogue, script: Path | None, standalone: bool = False):
        self.catalogue = catalogue
        self.script = Path(script) if script else None
        self._script_abs = os.path.abspath(str(script)) if script else None
        self.standalone = standalone
        self.nodes: list[Any] = []  # every builder object, in creation order
        self.environment: Any = None
        self.records: list[ScriptWarning] = []
        self._warned: set[str] = set()
        self._morse_only: list[tuple[Any, str, Any]] = []  # (owner or None for env, call, value)
        self.renamed = False
        self.finished = False

    # ---- where the script is

    def user_frame(self):
        """The innermost frame of the script (else the innermost frame outside the builder package)."""
        frame = sys._getframe(1)
        first_outside = None
        while frame is not None:
            filename = frame.f_code.co_filename
            if not is_builder_file(filename):
                if first_outside is None:
                    first_outside = frame
                if self._script_abs and os.path.abspath(filename) == self._script_abs:
                    return frame
            frame = frame.f_back
        return first_outside

    def caller_frame(self):
        """The innermost frame outside the builder package (the script, or a user's helper)."""
        frame = sys._getframe(1)
        while frame is not None and is_builder_file(frame.f_code.co_filename):
            frame = frame.f_back
        return frame

    def position(self) -> Position:
        frame = self.user_frame()
        if frame is None:
            return (str(self.script) if self.script else None, None, None)
        return frame_position(frame)

    def error(self, message: str) -> BuilderError:
        return BuilderError(message, *self.position())

    @property
    def warnings(self) -> list[str]:
        return [str(w) for w in self.records]

    def warn(self, key: str, message: str, position: Position | None = None) -> None:
        """A warning, once per `key` per script, at `position` (default: the script line running now)."""
        if key in self._warned:
            return
        self._warned.add(key)
        file, line, col = position or self.position()
        self.records.append(ScriptWarning(file, line, col, message))

    def morse_only(self, owner: Any, call: str, value: Any, reason: str | None = None,
                   shown: str | None = None) -> None:
        """A MORSE feature with no meaning in morsec: recorded in environment.morse_only, warned once
        (per call and kind of owner, or per `shown` text when given)."""
        self._morse_only.append((owner, call, jsonable(value)))
        label = f"{call}()" if owner is None else f"{type(owner).__name__}.{call}()"
        if shown is None:
            shown = f"env.{call}()" if owner is None else label
        else:
            label = shown
        why = reason or "has no meaning in morsec (Blender-only)"
        glue = "" if why.startswith(":") else " "
        self.warn(f"morse_only:{label}", f"{shown}{glue}{why}; accepted and recorded in environment.morse_only")

    # ---- objects

    def register(self, node: Any) -> None:
        frame = self.caller_frame()
        if frame is not None:
            self.scan(frame)
        # MORSE names objects after the script's variables when the Environment is constructed (and children at
        # append): a robot or object created after it keeps its default name (its .blend object's)
        node._after_environment = self.environment is not None
        self.nodes.append(node)

    def scan(self, frame_or_namespace) -> None:
        """Name unnamed, unparented objects after the variables that hold them (MORSE's close_context)."""
        names = _visible_names(frame_or_namespace if isinstance(frame_or_namespace, dict)
                               else frame_or_namespace.f_locals)
        for var, value in names.items():
            if var == "self" or not is_node(value) or value._kind == "environment":
                continue
            if (value._session is self and value._parent is None and value._auto_name is None
                    and not getattr(value, "_after_environment", False)):
                value._auto_name = var

    def name_from(self, frame, obj: Any) -> None:
        """Name `obj` after the variable that holds it in `frame` (MORSE's append)."""
        if frame is None or obj._auto_name is not None:
            return
        for var, value in _visible_names(frame.f_locals).items():
            if var != "self" and value is obj:
                obj._auto_name = var
                return

    def assign_names(self) -> None:
        """Final names: explicit or variable name, suffixed _001 ... when taken among siblings."""
        top = [n for n in self.nodes if n._parent is None and n._kind in ("robot", "object")]
        zones = [n for n in self.nodes if n._parent is None and n._kind == "zone"]
        for node in top:
            if node._explicit_name is None and node._auto_name is None and getattr(node, "_after_environment", False):
                node._auto_name = node._morse_default_name()
                self.warn(f"after_environment:{id(node)}",
                          f"{type(node).__name__}() is created after Environment(...): as in MORSE, it is not named "
                          f"after its variable but {node._auto_name!r} (create it before the Environment, or set "
                          "its name)", node._position)
        _dedupe(top)
        _dedupe(zones)
        for node in self.nodes:
            if node._children:
                _dedupe(node._children)
        self.renamed = True

    # ---- the scene

    def end_of_script(self, namespace: dict | None) -> None:
        if namespace is not None:
            self.scan(namespace)
        self.finished = True

    def recording(self) -> Recording:
        data, smap = self.scene_data()
        # in script order: some warnings (unknown properties kept as tags) are only known at the end
        ordered = sorted(self.records, key=lambda w: (w.file != str(self.script), w.line or 0, w.column or 0))
        return Recording(data, smap, ordered)

    def scene_data(self) -> tuple[dict, SourceMap]:
        self.assign_names()
        smap = SourceMap(str(self.script) if self.script else "<builder>")
        data: dict[str, Any] = {}

        for node in self.nodes:
            if node._parent is None and node._kind == "device":
                raise BuilderError(
                    f"{type(node).__name__} is not appended to a robot: call robot.append(...) "
                    f"(or append it to a FakeRobot())", *node._position)

        env: dict[str, Any] = {}
        if self.environment is not None:
            env = self.environment._emit(("environment",), smap)
        morse_only = self._morse_only_entries()
        if morse_only:
            env.setdefault("morse_only", {}).update(morse_only)
        if env:
            data["environment"] = env

        robots = [n for n in self.nodes if n._parent is None and n._kind == "robot"]
        objects = [n for n in self.nodes if n._parent is None and n._kind == "object"]
        zones = [n for n in self.nodes if n._parent is None and n._kind == "zone"]
        for key, nodes in (("robots", robots), ("objects", objects), ("zones", zones)):
            if nodes:
                data[key] = [node._emit((key, i), smap) for i, node in enumerate(nodes)]
        return data, smap

    def _morse_only_entries(self) -> dict:
        out: dict[str, Any] = {}
        for owner, call, value in self._morse_only:
            key = call if owner is None else f"{owner._label()}.{call}"
            out[key] = value
        return out


def _dedupe(nodes: list) -> None:
    taken: set[str] = set()
    for node in nodes:
        base = node._explicit_name or node._auto_name
        if base is None:
            node._final_name = None
            continue
        name, n = base, 0
        while name in taken:
            n += 1
            name = base + DUPLICATE_SUFFIX.format(n)
        taken.add(name)
        node._final_name = name


def frame_position(frame) -> Position:
    line = frame.f_lineno
    col = None
    try:
        positions = inspect.getframeinfo(frame, context=0).positions
        if positions is not None and positions.lineno == line and positions.col_offset is not None:
            col = positions.col_offset + 1
    except Exception:  # positions are a courtesy
        pass
    return frame.f_code.co_filename, line, col


def _visible_names(namespace) -> dict:
    """The variables a builder object can be named after: a namespace's, and inside a builder class's method
    (`self` a builder object) also that object's public attributes (MORSE named them so)."""
    names = dict(namespace)
    owner = names.get("self")
    if is_node(owner):
        return {**{k: v for k, v in vars(owner).items() if not k.startswith("_")}, **names}
    return names


def is_node(value: Any) -> bool:
    """Whether `value` is a builder object (an AbstractComponent: robot, device, object, zone, environment)."""
    return getattr(type(value), "_builder_node", False)


def jsonable(value: Any) -> Any:
    """A plain-data copy of a call's arguments (builder objects by name), for morse_only."""
    if is_node(value):
        return value.name
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items() if v is not None}
    if isinstance(value, (list, tuple, set, frozenset)):
        return [jsonable(v) for v in value if v is not None]
    if isinstance(value, (bool, int, float, str)):
        return value
    if value is None:
        return None
    return repr(value)


def join(*parts: str) -> str:
    return SEPARATOR.join(parts)
