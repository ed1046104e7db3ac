"""Files a scene needs besides its XML: meshes and textures from component folders, copied into the build
under assets/<kind>/<id>/ (formats MuJoCo does not read are converted to STL with trimesh)."""

from __future__ import annotations

import io
import os
from dataclasses import dataclass, field
from pathlib import Path

from morsec.errors import SceneError

NATIVE = {".stl", ".obj", ".msh", ".png"}  # MuJoCo reads these as they are
CONVERTED = {".dae", ".ply", ".glb", ".gltf", ".off", ".3mf"}  # trimesh turns these into STL


def asset_dir(cls) -> str:
    return f"assets/{cls.kind}s/{cls.id}"


def resource_path(cls) -> list[Path]:
    """Where a component's files are looked for: its folder, then $MORSE_RESOURCE_PATH (as MORSE)."""
    paths = [Path(cls.folder)]
    paths += [Path(p) for p in os.environ.get("MORSE_RESOURCE_PATH", "").split(os.pathsep) if p]
    return paths


@dataclass
class Assets:
    files: dict[str, bytes] = field(default_factory=dict)
    meshes: dict[str, tuple[str, list[float]]] = field(default_factory=dict)  # name -> (file, scale)

    def copy_folder(self, cls) -> None:
        """Every mesh and texture file of a component's folder, for its own assets.xml.j2 to use."""
        for path in sorted(Path(cls.folder).iterdir()):
            if path.is_file() and path.suffix.lower() in NATIVE | CONVERTED:
                self._add_file(cls, path)

    def mesh(self, cls, filename: str, scale: list[float]) -> str:
        """Declare a mesh file referenced by a robot's URDF; returns the MJCF mesh asset name."""
        path = self.find(cls, filename)
        target = self._add_file(cls, path)
        key = f"{cls.id}/{Path(target).stem}"
        if any(s != 1.0 for s in scale):
            key += "@" + "x".join(f"{s:g}" for s in scale)
        self.meshes[key] = (target, list(scale))
        return key

    def find(self, cls, filename: str) -> Path:
        relative = filename
        for prefix in ("file://", "package://"):
            if relative.startswith(prefix):
                relative = relative[len(prefix):]
                if prefix == "package://":  # package://<package>/<path>: the package is the component
                    relative = relative.split("/", 1)[1] if "/" in relative else relative
        candidate = Path(relative)
        if candidate.is_absolute():
            if candidate.is_file():
                return candidate
            searched = [candidate]
        else:
            searched = [base / candidate for base in resource_path(cls)]
            for path in searched:
                if path.is_file():
                    return path
        raise SceneError(f"{cls.kind} {cls.id!r}: asset file {filename!r} not found; searched: "
                         + ", ".join(str(p) for p in searched))

    def _add_file(self, cls, path: Path) -> str:
        suffix = path.suffix.lower()
        if suffix in CONVERTED:
            name = f"{asset_dir(cls)}/{path.stem}.stl"
            if name not in self.files:
                self.files[name] = _to_stl(path)
        elif suffix in NATIVE:
            name = f"{asset_dir(cls)}/{path.name}"
            if name not in self.files:
                self.files[name] = path.read_bytes()
        else:
            raise SceneError(f"{path}: unsupported asset format {suffix!r} (MuJoCo reads .stl .obj .msh; "
                             f"morsec converts {' '.join(sorted(CONVERTED))})")
        return name


def _to_stl(path: Path) -> bytes:
    try:
        import trimesh
        mesh = trimesh.load(str(path), force="mesh")
        buffer = io.BytesIO()
        mesh.export(buffer, file_type="stl")
    except Exception as err:  # trimesh raises many kinds of errors for files it cannot read
        raise SceneError(f"{path}: cannot convert this mesh to STL: {err}") from None
    return buffer.getvalue()
