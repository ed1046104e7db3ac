"""`morsec import-blend`: a user's .blend environment or props file as component folders of their project
(morsec.kits.blend reads the file and writes the folders), and `--list`, what a file holds as the importer
reads it."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from morsec.errors import MorsecError
from morsec.resources import PROJECT_FILE, project_component_dirs, project_root, search_path

KINDS = {"environment": "environments", "props": "props"}


def import_blend_file(source: Path, out: Path | None = None, kind: str = "environment", name: str | None = None,
                      force: bool = False) -> list[str]:
    """Import `source` into the components folder `out` (default: the project's); the lines to print."""
    from morsec.kits.blend.folder import ImportFailure, clean_id, import_blend
    from morsec.kits.blend.sdna import BlendFormatError
    folder_kind = _kind(kind)
    source = Path(source)
    if not source.is_file():
        raise MorsecError(f"{source}: no such file")
    root = Path(out) if out is not None else _project_components()
    try:
        _check_free(root, folder_kind, clean_id(name or source.stem))
        done = import_blend(source, root, folder_kind, name, force)
    except BlendFormatError as err:
        raise MorsecError(f"{source}: cannot import it: {err}") from None
    except ImportFailure as err:
        raise MorsecError(f"{source}: {err}") from None
    _refresh_schema(root)
    lines = [f"imported {source} ({done.objects} objects)"]
    for folder in done.folders:
        lines.append(f"  wrote {folder}")
    lines += [f"  note: {note}" for note in done.notes]
    if done.kind == "environments":
        lines += ["use it in a scene:", f"  environment: {{name: {done.id}}}",
                  "or in a builder script:", f"  env = Environment('{done.id}')"]
    else:
        first = done.props[0]
        obj = first.rsplit("/", 1)[-1]
        lines += [f"its props: {', '.join(done.props)}", "use one in a scene:",
                  f"  objects: [{{name: {obj.lower()}, type: {first}}}]", "or in a builder script:",
                  f"  {obj.lower()} = PassiveObject('props/{done.id}', '{obj}')"]
    if root.resolve() not in search_path(Path.cwd()):
        lines.append(f"({root} is not on the component search path here: list it in {PROJECT_FILE}'s components "
                     "or in $MORSEC_COMPONENTS)")
    return lines


def list_blend(source: Path, kind: str = "environment") -> list[str]:
    """What the importer reads in `source`: one line per object (kind, physics, collision bounds, mass, game
    properties), the objects an environment import takes (its scene's visible layers) or a props import (all)."""
    from morsec.kits.blend.scene import read_blend
    from morsec.kits.blend.sdna import BlendFormatError
    folder_kind = _kind(kind)
    try:
        scene = read_blend(Path(source), every_layer=folder_kind == "props")
    except BlendFormatError as err:
        raise MorsecError(f"{source}: cannot read it: {err}") from None
    except OSError as err:
        raise MorsecError(f"{source}: {err.strerror or err}") from None
    lines = [f"{source}: Blender {scene.version}, scene {scene.scene!r}, {len(scene.objects)} objects"]
    for obj in scene.objects:
        where = np.round(obj.matrix[:3, 3], 3).tolist()
        text = f"  {obj.name}: {obj.kind} at {where}"
        if obj.parent:
            text += f", child of {obj.parent}"
        if obj.kind in ("mesh", "empty"):
            text += f", {obj.physics.replace('_', ' ')}"
            if obj.collides and obj.kind == "mesh":
                text += f", bounds {obj.bounds.replace('_', ' ')}"
            if obj.moves:
                text += f", mass {obj.mass:.4g} kg, damping {obj.damping:.4g}, rotation damping " \
                        f"{obj.rotation_damping:.4g}"
        if obj.invisible:
            text += ", invisible"
        frictions = sorted({m.friction for m in obj.materials if m is not None and m.friction is not None})
        if frictions:
            text += f", friction {', '.join(f'{f:.4g}' for f in frictions)}"
        if obj.properties:
            text += f", properties {obj.properties}"
        if obj.custom:
            text += f", custom properties {obj.custom}"
        lines.append(text)
    return lines


def _check_free(root: Path, kind: str, ident: str) -> None:
    """The ids the import writes must not be another component's: the catalogue would hold them twice."""
    from morsec.component.catalogue import load_catalogue
    from morsec.kits.blend.folder import ImportFailure
    cat = load_catalogue(root)
    own = {kind: root.resolve() / kind / ident, "props": root.resolve() / "props" / ident}

    def ours(cls) -> bool:
        folder = Path(cls.folder).resolve()
        return folder == own[kind] or own["props"] in folder.parents

    # an environment is `ident` and its objects' props `ident/<object>`; a props file is only `ident/<object>`
    # (a catalogue prop named like the file, MORSE's `objects` table among them, is another id)
    taken = [cls for cls in cat.by_kind.get("environments", {}).values()
             if kind == "environments" and cls.id == ident and not ours(cls)]
    taken += [cls for cls in cat.by_kind.get("props", {}).values() if cls.id.startswith(ident + "/") and not ours(cls)]
    if taken:
        what = f"{taken[0].kind} {taken[0].id!r}"
        raise ImportFailure(f"{what} exists already ({taken[0].folder}): give this import another id with "
                            f"--name, e.g. --name my_{ident.replace('/', '_')}")


def _kind(kind: str) -> str:
    if kind not in KINDS:
        raise MorsecError(f"--kind {kind!r}: environment or props")
    return KINDS[kind]


def _project_components() -> Path:
    root = project_root(Path.cwd())
    if root is None:
        raise MorsecError(f"not in a morsec project (no {PROJECT_FILE} here or above): create one with "
                          "`morsec create NAME`, or give the components folder to write into with -o")
    return project_component_dirs(root)[0]


def _refresh_schema(components: Path) -> None:
    """The project's scene schema lists the new types (as after `morsec add`)."""
    from morsec.app.scaffold import write_schema
    root = project_root(components)
    if root is not None and components.resolve() in [d.resolve() for d in project_component_dirs(root)]:
        write_schema(root)
