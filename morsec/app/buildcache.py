"""A build folder that is up to date is not compiled again.

After a build of a YAML or TOML scene, a stamp in the user's cache folder ($XDG_CACHE_HOME/morsec/builds,
else ~/.cache/morsec/builds; one file per build folder, named by a hash of its absolute path; the build folder
itself holds only what its manifest lists) records a SHA-256 of everything the build was made from (the
scene file and its path, the catalogue's folders, $MORSE_ROOT's .blend files, morsec's own code and
templates, the Python and the installed distributions, MuJoCo's among them) and of the manifest written. A later
build of the same scene into the same folder that finds the same inputs, and in the folder exactly the files
its manifest lists, unchanged, stops there, without importing the compiler. A builder script (.py) runs every
time: it is code, and may read anything. Without a writable cache folder every build compiles."""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import sys
from pathlib import Path

from morsec.resources import classpath_roots, data_dir, morse_data, search_path

CACHE_DIR = "morsec/builds"  # under $XDG_CACHE_HOME or ~/.cache
MANIFEST = "manifest.json"  # morsec.scene.manifest.MANIFEST, which this module does not import (pydantic, MuJoCo)
CACHED_SUFFIXES = (".yaml", ".yml", ".toml")
_VERSION = b"morsec build inputs 1"
_PACKAGE = Path(__file__).resolve().parents[1]


def inputs_key(source: Path) -> str | None:
    """The SHA-256 of what a build of `source` is made from; None for a scene that is code (builder script)."""
    source = Path(source)
    if source.suffix not in CACHED_SUFFIXES:
        return None
    digest = hashlib.sha256(_VERSION)

    def add(part: str | bytes) -> None:
        data = part if isinstance(part, bytes) else part.encode("utf-8", "surrogateescape")
        digest.update(len(data).to_bytes(8, "little"))
        digest.update(data)

    try:
        add(str(source.resolve()))
        add(source.read_bytes())
        add(sys.version)
        for name in _distributions():
            add(name)
        morse = morse_data()  # $MORSE_ROOT's files answer names before the catalogue: they are inputs too
        add(str(morse))
        if morse is not None:
            for path in sorted(morse.rglob("*.blend")):
                stat = path.stat()
                add(f"{path} {stat.st_size} {stat.st_mtime_ns}")
        for root in (_PACKAGE, data_dir("templates"), *search_path(source.parent), *classpath_roots(source.parent)):
            add(str(root))
            for path in _files(root):
                add(path.relative_to(root).as_posix())
                add(path.read_bytes())
    except OSError:  # an unreadable input: build (and report it) as usual
        return None
    return digest.hexdigest()


def up_to_date(out_dir: Path, key: str | None) -> bool:
    """Whether `out_dir` was built from inputs `key` and still holds the files its manifest lists, unchanged."""
    if key is None:
        return False
    out_dir = Path(out_dir)
    try:
        stamp = json.loads(stamp_path(out_dir).read_text(encoding="utf-8"))
        manifest = (out_dir / MANIFEST).read_bytes()
        if stamp.get("inputs") != key or stamp.get("manifest") != sha256(manifest) \
                or stamp.get("folder") != str(out_dir.resolve()):
            return False
        files = json.loads(manifest)["files"]
        return holds(out_dir, {**files, MANIFEST: stamp["manifest"]})
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return False


def holds(out_dir: Path, files: dict[str, str]) -> bool:
    """Whether `out_dir` holds these files ({relative path: SHA-256}) and no other."""
    held = {Path(folder, f).relative_to(out_dir).as_posix() for folder, _, names in os.walk(out_dir) for f in names}
    if held != set(files):  # a file added since: a build would remove it
        return False
    try:
        return all(sha256((out_dir / name).read_bytes()) == digest for name, digest in files.items())
    except OSError:
        return False


def record(out_dir: Path, key: str | None) -> None:
    """Write the stamp of a build just written from inputs `key` (nothing for a builder script)."""
    if key is None:
        return
    out_dir = Path(out_dir)
    path = stamp_path(out_dir)
    tmp = path.with_name(f"{path.name}.{os.getpid()}")
    try:
        stamp = {"folder": str(out_dir.resolve()), "inputs": key,
                 "manifest": sha256((out_dir / MANIFEST).read_bytes())}
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp.write_text(json.dumps(stamp, indent=2, sort_keys=True) + "\n", encoding="utf-8")
        tmp.replace(path)
    except OSError:  # no cache: the next build compiles again
        with contextlib.suppress(OSError):
            tmp.unlink(missing_ok=True)


def stamp_path(out_dir: Path) -> Path:
    """The stamp of build folder `out_dir`, in the user's cache folder."""
    cache = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    name = hashlib.sha256(str(Path(out_dir).resolve()).encode("utf-8", "surrogateescape")).hexdigest()
    return Path(cache, CACHE_DIR, f"{name}.json")


def _files(root: Path) -> list[Path]:
    """Every file under `root`, sorted, without bytecode caches and hidden entries."""
    found = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__" and not d.startswith("."))
        found.extend(Path(folder, f) for f in sorted(files) if not f.startswith(".") and not f.endswith(".pyc"))
    return found


def _distributions() -> list[str]:
    """The installed distributions with their versions (their metadata folders' names), where Python looks."""
    names = []
    for folder in sys.path:
        try:
            with os.scandir(folder or ".") as it:
                names.extend(sorted(f"{folder}:{e.name}" for e in it if e.name.endswith((".dist-info", ".egg-info"))))
        except OSError:
            continue
    return names


def sha256(data: str | bytes) -> str:
    return hashlib.sha256(data if isinstance(data, bytes) else data.encode("utf-8")).hexdigest()
