"""Where the shipped data folders live, installed (inside the package) or in a source checkout; where
components are searched for (the catalogue's search path), and the entry points of other packages.
Nothing here imports more than the standard library: a build that is up to date is decided from these."""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

from morsec.errors import MorsecError

_PACKAGE = Path(__file__).resolve().parent
PROJECT_FILE = "morsec.toml"
ENV_VAR = "MORSEC_COMPONENTS"
ENTRY_POINT_GROUP = "morsec.components"
MORSE_ROOT_VAR = "MORSE_ROOT"  # a MORSE installation, whose share/morse/data holds MORSE's .blend files


def data_dir(name: str) -> Path:
    """`components`, `templates` or `schemas`: inside the wheel, else beside the package in the source tree."""
    for candidate in (_PACKAGE / name, _PACKAGE.parent / name):
        if candidate.is_dir():
            return candidate
    raise FileNotFoundError(f"morsec data folder {name!r} not found beside {_PACKAGE}")


def entry_points_of(group: str) -> list:
    """The entry points of `group` that importlib.metadata.entry_points(group=...) gives, sorted by name.
    Only the distributions whose entry_points.txt names the group are read: importlib.metadata reads the
    metadata of every installed distribution, tens of milliseconds of a start-up."""
    from importlib.metadata import Distribution
    header = f"[{group}]"
    seen: set[str] = set()
    found = []
    for folder in sys.path:
        try:
            with os.scandir(folder or ".") as it:
                entries = sorted((e.name, e.path) for e in it if e.name.endswith((".dist-info", ".egg-info")))
        except OSError:
            continue
        for name, path in entries:
            project = re.sub(r"[-_.]+", "_", name.rpartition(".")[0].split("-")[0]).lower()
            if project in seen:  # the first distribution of a name on sys.path is the one installed
                continue
            seen.add(project)
            try:
                text = Path(path, "entry_points.txt").read_text(encoding="utf-8")
            except OSError:
                continue
            if header in text:
                found.extend(Distribution.at(path).entry_points.select(group=group))
    return sorted(found, key=lambda e: e.name)


def project_root(start: Path) -> Path | None:
    """The nearest folder at or above `start` holding a `morsec.toml` project file."""
    start = start.resolve()
    for folder in (start, *start.parents):
        if (folder / PROJECT_FILE).is_file():
            return folder
    return None


def project_component_dirs(root: Path) -> list[Path]:
    import tomllib  # a project's file only: a run of a build folder does not read one
    with open(root / PROJECT_FILE, "rb") as f:
        try:
            config = tomllib.load(f)
        except tomllib.TOMLDecodeError as err:
            raise MorsecError(f"{root / PROJECT_FILE}: {err}") from None
    dirs = config.get("project", {}).get("components", ["components"])
    return [(root / d) for d in dirs]


def search_path(start: Path | None = None) -> tuple[Path, ...]:
    """The catalogue's folders: built-ins, then entry points, then $MORSEC_COMPONENTS, then the project's
    folders (from `start` up)."""
    paths = [data_dir("components")]
    for ep in entry_points_of(ENTRY_POINT_GROUP):
        target = ep.load()
        paths.append(Path(target() if callable(target) else target))
    for item in os.environ.get(ENV_VAR, "").split(os.pathsep):
        if item:
            paths.append(Path(item))
    root = project_root(start if start is not None else Path.cwd())
    if root is not None:
        paths.extend(project_component_dirs(root))
    unique: list[Path] = []
    for p in paths:
        p = p.resolve()
        if p not in unique and p.is_dir():
            unique.append(p)
    return tuple(unique)


MORSE_SIM_SCRIPT = "default.py"  # what `morse create NAME` writes: NAME/default.py, NAME/src/NAME/..., NAME/scripts/
MORSE_SIM_SOURCES = "src"


def morse_simulation(start: Path) -> Path | None:
    """The folder of a MORSE simulation (laid out by `morse create`: `default.py` beside a `src/` folder) at or
    above `start` (a folder or a file in it), or None."""
    start = Path(start).resolve()
    for folder in ((start,) if start.is_dir() else ()) + tuple(start.parents):
        if (folder / MORSE_SIM_SCRIPT).is_file() and (folder / MORSE_SIM_SOURCES).is_dir():
            return folder
    return None


def classpath_roots(start: Path | None = None) -> tuple[Path, ...]:
    """The folders whose Python packages hold MORSE-API components (classes named by a dotted class path): the
    `src/` of the MORSE simulation `start` is in. Put on sys.path to import them."""
    sim = morse_simulation(start if start is not None else Path.cwd())
    return (sim / MORSE_SIM_SOURCES,) if sim is not None else ()


def scene_source(path: Path) -> Path:
    """What a scene path names: a MORSE simulation's folder (`morsec run mysim`, as `morse run mysim`) is its
    `default.py`; anything else is itself."""
    path = Path(path)
    if path.is_dir() and (path / MORSE_SIM_SCRIPT).is_file() and (path / MORSE_SIM_SOURCES).is_dir():
        return path / MORSE_SIM_SCRIPT
    return path


def morse_data() -> Path | None:
    """$MORSE_ROOT/share/morse/data when $MORSE_ROOT names a MORSE installation (its environments and props
    are then MORSE's own .blend files: morsec.component.morse_data), else None."""
    root = os.environ.get(MORSE_ROOT_VAR)
    if not root:
        return None
    data = Path(root) / "share" / "morse" / "data"
    return data.resolve() if data.is_dir() else None
