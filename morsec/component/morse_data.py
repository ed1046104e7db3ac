"""A MORSE installation's own environments and props, when $MORSE_ROOT names one: the `.blend` files under
`$MORSE_ROOT/share/morse/data/environments/` and `props/`, read by morsec import-blend's reader the first time
a scene names them and kept, as component folders, in the user's cache ($XDG_CACHE_HOME/morsec/morse-data,
else ~/.cache/morsec/morse-data; made again when the file changes). Their names are MORSE's:
`Environment('indoors-1/indoor-1')`, `PassiveObject('props/objects', 'RollingChair')` (the prop
`objects/RollingChair`). While $MORSE_ROOT is set they take precedence over the catalogue's components of the
same names; without it, names are the catalogue's alone."""

from __future__ import annotations

import hashlib
import json
import os
import sys
from collections.abc import Callable
from pathlib import Path

from morsec.errors import MorsecError
from morsec.resources import MORSE_ROOT_VAR

FOLDER = "MORSE_ROOT"  # under the cache root: the template names of these components are unlike any catalogue's


class MorseData:
    def __init__(self, data: Path):
        self.data = data
        self.files: dict[str, dict[str, Path]] = {"environments": {}, "props": {}}
        for kind in self.files:
            base = data / kind
            if base.is_dir():
                for path in sorted(base.rglob("*.blend")):
                    self.files[kind][path.relative_to(base).with_suffix("").as_posix()] = path
        digest = hashlib.sha256(str(data.resolve()).encode("utf-8", "surrogateescape")).hexdigest()[:16]
        cache = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
        self.root = Path(cache, "morsec", "morse-data", digest)  # a template root of the catalogue
        self.loaded: dict[tuple[str, str], list[tuple[str, str, type]]] = {}

    def ids(self, kind: str) -> list[str]:
        """The environments MORSE's data holds (props are known once their file is read)."""
        return sorted(self.files["environments"]) if kind == "environments" else []

    def source(self, kind: str, name: str) -> tuple[str, str] | None:
        """(kind of file, file id) of the MORSE file a component name comes from: an environment's own name,
        `<props file>/<object>`, or `<environment>/<object>` for an environment's passive object."""
        text = name.replace("\\", "/").removesuffix(".blend")
        text = text.removeprefix(f"{kind}/")
        if kind == "environments":
            return ("environments", text) if text in self.files["environments"] else None
        if kind != "props" or "/" not in text:
            return None
        head = text.rsplit("/", 1)[0]
        for file_kind in ("props", "environments"):
            if head in self.files[file_kind]:
                return file_kind, head
        return None

    def load(self, load_component: Callable[[Path, str, str], type], file_kind: str,
             file_id: str) -> list[tuple[str, str, type]]:
        """The components made of one MORSE file, imported into the cache if it is not there or is stale, and
        loaded by the catalogue's `load_component`: [(kind, id, class)]."""
        if (file_kind, file_id) in self.loaded:
            return self.loaded[file_kind, file_id]
        from morsec.kits.blend.folder import IMPORTER, import_blend
        from morsec.kits.blend.sdna import BlendFormatError
        source = self.files[file_kind][file_id]
        base = self.root / FOLDER
        stamp_path = self.root / "stamps" / file_kind / f"{file_id}.json"
        stat = source.stat()
        stamp = {"source": str(source), "size": stat.st_size, "mtime_ns": stat.st_mtime_ns, "importer": IMPORTER}
        try:
            fresh = json.loads(stamp_path.read_text(encoding="utf-8")) == stamp
        except (OSError, ValueError):
            fresh = False
        if not fresh:
            try:
                import_blend(source, base, file_kind, file_id, replace=True)
            except BlendFormatError as err:
                raise MorsecError(f"{source} (${MORSE_ROOT_VAR}): cannot read it: {err}") from None
            except Exception as err:  # noqa: BLE001 (ImportFailure and OSError: one line)
                raise MorsecError(f"{source} (${MORSE_ROOT_VAR}): cannot import it: {err}") from None
            stamp_path.parent.mkdir(parents=True, exist_ok=True)
            stamp_path.write_text(json.dumps(stamp) + "\n", encoding="utf-8")
        found = []
        folders = [("environments", base / "environments" / file_id)] if file_kind == "environments" else []
        props_base = base / "props"
        folders += [("props", f.parent) for f in sorted((props_base / file_id).rglob("component.py"))]
        for kind, folder in folders:
            cid = folder.relative_to(base / kind).as_posix()
            found.append((kind, cid, load_component(folder, kind, cid)))
        self.loaded[file_kind, file_id] = found
        what = "environment" if file_kind == "environments" else "props file"
        print(f"morsec: {what} {file_id!r} is MORSE's {source} (${MORSE_ROOT_VAR}), read by morsec "
              "import-blend's reader", file=sys.stderr)
        return found
