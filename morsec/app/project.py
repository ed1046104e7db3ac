"""From what the user names (a scene file or a build folder) to a build folder: load, compile, write.
The front ends and the compiler are imported only when something is to be built: running a build folder,
or building a scene whose build is up to date (morsec.app.buildcache), does not load them."""

from __future__ import annotations

import contextlib
import fcntl
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from morsec.app import buildcache
from morsec.app.buildcache import MANIFEST
from morsec.resources import MORSE_SIM_SCRIPT, scene_source

if TYPE_CHECKING:
    from morsec.component.catalogue import Catalogue


def default_build_dir(source: Path) -> Path:
    """build/<scene name>; a MORSE simulation's default.py (`morsec run mysim`) is built as build/mysim."""
    source = scene_source(Path(source))
    if source.name == MORSE_SIM_SCRIPT and scene_source(source.parent) == source:
        return Path("build") / source.resolve().parent.name
    return Path("build") / source.stem


def build_scene(source: Path, out_dir: Path, catalogue: Catalogue | None = None) -> Path:
    """Compile a scene file into `out_dir` (replaced only once the new build is complete); nothing is done
    when `out_dir` is an up-to-date build of it."""
    source = scene_source(Path(source))
    key = buildcache.inputs_key(source) if catalogue is None else None
    if buildcache.up_to_date(out_dir, key):
        return Path(out_dir)
    from morsec.compiler.build import compile_scene, write_build
    from morsec.component.catalogue import load_catalogue
    from morsec.frontends.load import load_scene
    cat = catalogue or load_catalogue(source.parent)
    write_build(compile_scene(load_scene(source, cat), cat), Path(out_dir))
    buildcache.record(out_dir, key)
    return Path(out_dir)


def check_scene(source: Path, strict: bool = False) -> None:
    """Everything `build` checks, nothing written; `strict`: a builder script's warnings are errors."""
    from morsec.compiler.build import compile_scene
    from morsec.component.catalogue import load_catalogue
    from morsec.frontends.load import load_scene
    source = scene_source(Path(source))
    cat = load_catalogue(source.parent)
    compile_scene(load_scene(source, cat, strict), cat)


def prepare_build(source: Path, out: Path | None = None) -> Path:
    """A build folder for `source`: itself if it is one, else compiled (rewritten only when it changed)."""
    source = Path(source)
    if source.is_dir() and (source / MANIFEST).is_file():
        return source
    out_dir = Path(out) if out else default_build_dir(source)
    source = scene_source(source)
    out_dir = Path(out) if out else default_build_dir(source)
    key = buildcache.inputs_key(source)
    if buildcache.up_to_date(out_dir, key):
        return out_dir
    from morsec.compiler.build import compile_scene, write_build
    from morsec.component.catalogue import load_catalogue
    from morsec.frontends.load import load_scene
    cat = load_catalogue(source.parent)
    files = compile_scene(load_scene(source, cat), cat)
    with _building(out_dir):  # the nodes of a multinode scene start side by side from the same scene file
        if not _same(out_dir, files):
            write_build(files, out_dir)
    buildcache.record(out_dir, key)
    return out_dir


@contextlib.contextmanager
def _building(out_dir: Path) -> Iterator[None]:
    """One process at a time compares and writes `out_dir` (a lock file beside it): a second one finds the
    first one's build, the same as its own, and leaves it alone."""
    try:
        out_dir.parent.mkdir(parents=True, exist_ok=True)
        lock = open(out_dir.parent / f".{out_dir.name}.lock", "a")  # noqa: SIM115
    except OSError:  # a read-only place: write_build says why
        yield
        return
    with lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        yield


def _same(out_dir: Path, files: dict[str, str | bytes]) -> bool:
    """Whether `out_dir` holds exactly `files` (a file edited or added there since: it is written again)."""
    try:
        if (out_dir / MANIFEST).read_text(encoding="utf-8") != files[MANIFEST]:
            return False
        return buildcache.holds(out_dir, {name: buildcache.sha256(content) for name, content in files.items()})
    except OSError:
        return False
