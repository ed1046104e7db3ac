"""Component folders from a .blend file: what `morsec import-blend` writes, and what the catalogue makes of a
MORSE installation's files when $MORSE_ROOT is set.

An environment file becomes `environments/<id>/`: its static objects drawn (one mesh per object and material,
in the world frame) and collided (the collision bounds Blender's game engine gave them: boxes, spheres,
cylinders, capsules, hulls, or a triangle mesh cut into convex pieces), its lamps as lights. Its objects that
move (dynamic and rigid bodies) or carry game properties (what MORSE's sensors look for: Object, Label, Type
...) become passive objects of the environment, each a prop `props/<id>/<object>/` with its children: they
keep their names and properties, their mass and the physics type. A props file becomes one prop per object
without a parent, `props/<id>/<object>/`, whatever layer holds it (as MORSE's PassiveObject takes them).

Everything is made in memory, then written into a staging folder beside the targets and moved into place:
a file that cannot be read leaves nothing behind."""

from __future__ import annotations

import io
import json
import os
import re
import shutil
import struct
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from morsec.constants import FORBIDDEN_NAME_CHARS
from morsec.kits.blend.scene import BlendObject, BlendScene, read_blend
from morsec.kits.convex import convex_pieces, hull_piece
from morsec.kits.geometry import fmt, fmt_vec, matrix_to_euler, matrix_to_quat

KINDS = ("environments", "props")
IMPORTER = 1  # raised when what an import writes changes: $MORSE_ROOT's cached imports are made again
RECORD = "blend-import.json"  # what the import read and made, beside component.py
DEFAULT_COLOR = (0.8, 0.8, 0.8, 1.0)  # Blender's colour of a face without material
DEFAULT_FRICTION = 0.5  # Blender 2.6x's material friction
# Blender's friction runs to 100; MuJoCo's pyramidal contacts lose their hold above a few (a ball of friction 8
# sinks through the floor), so a material's friction is carried up to this
MAX_FRICTION = 2.0
MAX_LIGHTS = 8
CONE_SIDES = 16
NAME_CHARS = re.compile(r"[^A-Za-z0-9_.\-]")


class ImportFailure(Exception):
    """The folders cannot be written (they exist, or the file names nothing to import); one line."""


@dataclass
class Visual:
    mesh: str  # the mesh file's stem in the folder
    rgba: tuple[float, ...]
    main: bool  # of the owner's first material: the scene's `color` paints it


@dataclass
class Collider:
    type: str  # box, sphere, cylinder, capsule, mesh
    pos: np.ndarray
    quat: np.ndarray
    size: list[float]  # MuJoCo's size (half extents, radius ...); [] for a mesh
    points: np.ndarray | None  # a mesh's points (MuJoCo takes their hull)
    volume: float
    friction: float


@dataclass
class Shape:
    """What one owner (the world, or a passive object) draws and collides with, in its own frame."""

    visuals: list[Visual] = field(default_factory=list)
    colliders: list[Collider] = field(default_factory=list)
    files: dict[str, bytes] = field(default_factory=dict)  # mesh files (binary STL)
    notes: list[str] = field(default_factory=list)


@dataclass
class Imported:
    kind: str
    id: str  # the environment's id, or the props file's folder under props/
    props: list[str]  # prop ids written
    objects: int  # objects read from the file
    folders: list[Path]
    notes: list[str]  # what was approximated, one line each


def import_blend(source: Path, root: Path, kind: str = "environments", name: str | None = None,
                 replace: bool = False) -> Imported:
    """Write the component folders of `source` under the catalogue folder `root`; `name` is the environment's
    id (or the props file's folder), by default the file's stem."""
    if kind not in KINDS:
        raise ImportFailure(f"unknown kind {kind!r}: environments or props")
    scene = read_blend(Path(source), every_layer=kind == "props")
    ident = clean_id(name or Path(source).stem)
    files: dict[str, bytes] = {}  # path under root -> content
    notes: list[str] = []
    props: list[str] = []
    env_dir = f"environments/{ident}"
    props_dir = f"props/{ident}"
    owners = _owners(scene, kind)
    if kind == "props" and not owners:
        raise ImportFailure(f"{source}: no object with a mesh to import as a prop")
    entries = []
    folder_names: set[str] = set()
    scene_names: set[str] = set()
    for top, members in owners.items():
        folder = _unique(NAME_CHARS.sub("_", top.name), folder_names)
        pid = f"{ident}/{folder}"
        frame = _frame(top.matrix)
        shape = _shape(members, frame, top)
        notes += shape.notes
        _write_prop(files, f"{props_dir}/{folder}", pid, top, shape, scene)
        props.append(pid)
        if kind == "environments":
            entries.append({"name": _unique(_scene_name(top.name), scene_names), "type": pid,
                            "translate": _vec(frame[:3, 3]), "rotate": _vec(matrix_to_euler(frame[:3, :3]))})
    if kind == "environments":
        world = [o for o in scene.objects if not any(o in m for m in owners.values())]
        shape = _shape(world, np.eye(4), None)
        notes += shape.notes
        _write_environment(files, env_dir, ident, scene, shape, entries, world)
    for obj in scene.objects:
        notes += [f"{obj.name}: {n}" for n in obj.notes]
    targets = [env_dir] if kind == "environments" else []
    if props:
        targets.append(props_dir)
    _write(Path(root), files, targets, replace)
    return Imported(kind, ident, props, len(scene.objects), [Path(root) / t for t in targets], notes)


def clean_id(text: str) -> str:
    parts = [NAME_CHARS.sub("_", p) for p in text.replace("\\", "/").removesuffix(".blend").split("/") if p]
    if not parts or any(p in (".", "..") for p in parts):
        raise ImportFailure(f"{text!r} cannot name a component")
    return "/".join(parts)


# ---- which object goes where

def _owners(scene: BlendScene, kind: str) -> dict[BlendObject, list[BlendObject]]:
    """Each passive object (top object) with the objects it carries (itself and its descendants)."""
    by_name = scene.by_name()
    children: dict[str | None, list[BlendObject]] = {}
    for obj in scene.objects:
        parent = obj.parent if obj.parent in by_name else None
        children.setdefault(parent, []).append(obj)

    def subtree(obj: BlendObject) -> list[BlendObject]:
        out, stack = [], [obj]
        while stack:
            o = stack.pop()
            out.append(o)
            stack.extend(children.get(o.name, []))
        return out

    def drawn(objs: list[BlendObject]) -> bool:
        return any(o.mesh is not None and len(o.mesh.triangles) for o in objs)

    owners: dict[BlendObject, list[BlendObject]] = {}

    def visit(obj: BlendObject) -> None:
        members = subtree(obj)
        passive = kind == "props" or obj.moves or bool(obj.properties)
        if passive and drawn(members):
            owners[obj] = members
            return
        for child in children.get(obj.name, []):
            visit(child)

    for obj in children.get(None, []):
        visit(obj)
    return owners


def _frame(matrix: np.ndarray) -> np.ndarray:
    """The object's position and orientation without its scale (the nearest rotation to its matrix)."""
    u, _, vt = np.linalg.svd(matrix[:3, :3])
    rotation = u @ vt
    if np.linalg.det(rotation) < 0:
        u[:, -1] *= -1
        rotation = u @ vt
    frame = np.eye(4)
    frame[:3, :3] = rotation
    frame[:3, 3] = matrix[:3, 3]
    return frame


# ---- shapes

def _shape(members: list[BlendObject], frame: np.ndarray, top: BlendObject | None) -> Shape:
    shape = Shape()
    inverse = np.linalg.inv(frame)
    main = _main_material(members) if top is not None else None
    stems: set[str] = set()
    for obj in members:
        if obj.kind not in ("mesh", "empty") and obj.mesh is None:
            continue
        relative = inverse @ obj.matrix
        if obj.mesh is not None and len(obj.mesh.triangles) and not obj.invisible:
            _visuals(shape, obj, relative, main, stems)
        if obj.mesh is not None and len(obj.mesh.triangles) and obj.collides:
            _colliders(shape, obj, relative)
    if top is not None and top.moves and not shape.colliders:
        shape.notes.append(f"{top.name}: moves but nothing of it collides: it falls through everything")
    return shape


def _main_material(members: list[BlendObject]) -> object:
    """The material `color` stands for: the first one of the first object drawn (the top object's own when
    it is drawn)."""
    for obj in members:
        if obj.mesh is not None and len(obj.mesh.triangles) and not obj.invisible:
            for slot in np.unique(obj.mesh.slots):
                if 0 <= slot < len(obj.materials) and obj.materials[slot] is not None:
                    return obj.materials[slot]
    return None


def _first_material(obj: BlendObject) -> object:
    return next((m for m in obj.materials if m is not None), None)


def _visuals(shape: Shape, obj: BlendObject, relative: np.ndarray, main, stems: set[str]) -> None:
    mesh = obj.mesh
    assert mesh is not None
    points = mesh.vertices @ relative[:3, :3].T + relative[:3, 3]
    flipped = np.linalg.det(relative[:3, :3]) < 0  # a mirroring scale turns faces inside out
    for slot in np.unique(mesh.slots):
        tris = mesh.triangles[mesh.slots == slot]
        if flipped:
            tris = tris[:, ::-1]
        material = obj.materials[slot] if 0 <= slot < len(obj.materials) else None
        stem = _unique(NAME_CHARS.sub("_", obj.name) + (f".{slot}" if len(obj.materials) > 1 else ""), stems)
        shape.files[f"{stem}.stl"] = _stl(points[tris])
        rgba = tuple(material.color) if material is not None else DEFAULT_COLOR
        shape.visuals.append(Visual(stem, rgba, material is not None and material is main))


def _colliders(shape: Shape, obj: BlendObject, relative: np.ndarray) -> None:
    mesh = obj.mesh
    assert mesh is not None
    material = _first_material(obj)
    friction = getattr(material, "friction", None)
    friction = DEFAULT_FRICTION if friction is None else friction
    if friction > MAX_FRICTION:
        shape.notes.append(f"{obj.name}: material friction {friction:g} carried as {MAX_FRICTION:g}")
        friction = MAX_FRICTION
    local = mesh.vertices
    low, high = local.min(axis=0), local.max(axis=0)
    centre = relative[:3, :3] @ ((low + high) / 2) + relative[:3, 3]
    axes = relative[:3, :3]
    scale = np.linalg.norm(axes, axis=0)
    rotation = _frame(relative)[:3, :3]
    quat = matrix_to_quat(rotation)
    half = (high - low) / 2 * scale
    bounds = obj.bounds
    if bounds == "box":
        shape.colliders.append(Collider("box", centre, quat, list(np.maximum(half, 1e-3)), None,
                                        float(np.prod(2 * np.maximum(half, 1e-3))), friction))
    elif bounds == "sphere":
        if obj.moves and not obj.bounds_set:  # the game engine's default: a sphere of the object's Radius
            radius, centre = obj.radius * float(scale.max()), relative[:3, 3]
        else:
            radius = float(half.max())
        radius = max(radius, 1e-3)
        shape.colliders.append(Collider("sphere", centre, np.array([1.0, 0, 0, 0]), [radius], None,
                                        4 / 3 * np.pi * radius ** 3, friction))
    elif bounds in ("cylinder", "capsule"):
        radius = max(float(max(half[0], half[1])), 1e-3)
        length = float(half[2]) if bounds == "cylinder" else max(float(half[2]) - radius, 0.0)
        if bounds == "capsule" and length == 0.0:
            shape.colliders.append(Collider("sphere", centre, quat, [radius], None, 4 / 3 * np.pi * radius ** 3,
                                            friction))
        else:
            shape.colliders.append(Collider(bounds, centre, quat, [radius, max(length, 1e-3)], None,
                                            np.pi * radius ** 2 * 2 * max(length, 1e-3), friction))
    elif bounds == "cone":
        radius, height = float(max(half[0], half[1])), float(half[2])
        angles = np.linspace(0, 2 * np.pi, CONE_SIDES, endpoint=False)
        base = np.stack([radius * np.cos(angles), radius * np.sin(angles), np.full(CONE_SIDES, -height)], axis=1)
        points = np.concatenate([base, [[0.0, 0.0, height]]]) @ rotation.T + centre
        shape.colliders.append(Collider("mesh", np.zeros(3), np.array([1.0, 0, 0, 0]), [], points,
                                        np.pi * radius ** 2 * 2 * height / 3, friction))
    else:
        points = local @ axes.T + relative[:3, 3]
        pieces = [hull_piece(points)] if bounds == "convex_hull" else convex_pieces(points, mesh.triangles)
        for piece in pieces:
            shape.colliders.append(Collider("mesh", np.zeros(3), np.array([1.0, 0, 0, 0]), [], piece.points,
                                            piece.volume, friction))


def _stl(triangles: np.ndarray) -> bytes:
    """Binary STL of (n, 3, 3) corner coordinates, normals from the corners' order."""
    tris = np.asarray(triangles, np.float32)
    normals = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    length = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.where(length > 0, normals / np.maximum(length, 1e-30), 0).astype(np.float32)
    record = np.zeros(len(tris), dtype=[("n", "<f4", (3,)), ("v", "<f4", (3, 3)), ("a", "<u2")])
    record["n"], record["v"] = normals, tris
    out = io.BytesIO()
    out.write(b"morsec import-blend".ljust(80, b" "))
    out.write(struct.pack("<I", len(tris)))
    out.write(record.tobytes())
    return out.getvalue()


# ---- files

def _write_environment(files: dict[str, bytes], folder: str, ident: str, scene: BlendScene, shape: Shape,
                       entries: list[dict], world: list[BlendObject]) -> None:
    for name, data in shape.files.items():
        files[f"{folder}/{name}"] = data
    lights = _lights(world)
    body = [f"<!-- {_comment(ident)}: the static objects of {_comment(scene.path.name)} (Blender {scene.version}), "
            "imported by morsec import-blend; see README.md -->"]
    body += lights or ['<light name="sun" pos="0 0 30" dir="0 0 -1" directional="true" diffuse="0.7 0.7 0.7" '
                       'specular="0.1 0.1 0.1" castshadow="true"/>']
    body += _geoms(shape, "{{ id }}", prefix="env/", scaled=False)
    files[f"{folder}/environment.xml.j2"] = _text(body)
    assets = _mesh_assets(shape, scaled=False)
    assets.append('<texture name="skybox" type="skybox" builtin="gradient" rgb1="0.5 0.65 0.85" rgb2="0.1 0.15 0.25" '
                  'width="512" height="512"/>')
    files[f"{folder}/assets.xml.j2"] = _text(assets)
    drawn = [o.name for o in world if o.mesh is not None and len(o.mesh.triangles)]
    low, high = _extents(world)
    record = {"source": scene.path.name, "blender": scene.version, "scene": scene.scene, "objects": entries,
              "static": drawn, "extents": [low, high]}
    files[f"{folder}/{RECORD}"] = (json.dumps(record, indent=1) + "\n").encode()
    cls = _class_name(ident)
    doc = (f"{scene.path.name} (Blender {scene.version}) imported by morsec import-blend: {len(drawn)} static "
           f"objects, {len(entries)} passive objects (the environment's `objects`), {len(lights)} lights.")
    files[f"{folder}/component.py"] = _text([
        f'"""{_py(doc)} See README.md."""', "", "import json", "from pathlib import Path", "",
        "from morsec.component import Environment", "",
        f'_RECORD = json.loads((Path(__file__).parent / "{RECORD}").read_text(encoding="utf-8"))', "", "",
        f"class {cls}(Environment):",
        f'    """{_py(doc)}"""', "",
        f"    short_descr = {json.dumps(f'{scene.path.name}, imported')}",
        '    objects = tuple(_RECORD["objects"])', "", "",
        f"COMPONENT = {cls}"])
    files[f"{folder}/README.md"] = _text([
        f"# {ident}", "",
        f"Imported by `morsec import-blend` from `{scene.path.name}` (Blender {scene.version}, scene "
        f"`{scene.scene}`). Extents of its static objects: x {low[0]:.2f} to {high[0]:.2f} m, y {low[1]:.2f} to "
        f"{high[1]:.2f} m, z {low[2]:.2f} to {high[2]:.2f} m.", "",
        f"Static objects, drawn and collided as Blender's game engine did: {_names(drawn)}.", "",
        f"Passive objects (the objects that move or carry game properties, each a prop under `props/{ident}/`): "
        f"{_names([e['name'] for e in entries])}.", "",
        "Regenerate this folder with `morsec import-blend` rather than editing it: see docs/importing-blend.md."])


def _write_prop(files: dict[str, bytes], folder: str, pid: str, top: BlendObject, shape: Shape,
                scene: BlendScene) -> None:
    for name, data in shape.files.items():
        files[f"{folder}/{name}"] = data
    low, high = _bounds(shape)
    size = _vec([max(float(h - lo), 1e-3) for lo, h in zip(low, high)])
    color = list(next((v.rgba for v in shape.visuals if v.main), DEFAULT_COLOR))
    defaults: dict = {"size": _vec(size), "color": _vec(color), "dynamic": top.moves}
    if top.moves:
        defaults["mass"] = float(f"{top.mass:.6g}")
    # Blender's custom (ID) properties of plain values, then the game properties MORSE's sensors read
    bag = {k: v for k, v in top.custom.items() if isinstance(v, bool | int | float | str)} | top.properties
    if bag:
        defaults["properties"] = bag
    body = [f"{{#- {_comment(top.name)} of {_comment(scene.path.name)} (Blender {scene.version}) with its children, "
            "in its frame, imported by morsec import-blend; `size` scales it, `color` paints its first material -#}",
            f"{{% set own = {json.dumps(size)} %}}",
            "{% set s = [size[0] / own[0], size[1] / own[1], size[2] / own[2]] %}",
            "{% set tag = '' if s == [1.0, 1.0, 1.0] else '@' ~ (s | v) | replace(' ', 'x') %}"]
    total = sum(c.volume for c in shape.colliders) or 1.0
    body += _geoms(shape, "{{ id }}", prefix=None, scaled=True, total=total)
    files[f"{folder}/model.xml.j2"] = _text(body)
    assets = [f"{{% set own = {json.dumps(size)} %}}",
              "{% for size in sizes %}",
              "{% set s = [size[0] / own[0], size[1] / own[1], size[2] / own[2]] %}",
              "{% set tag = '' if s == [1.0, 1.0, 1.0] else '@' ~ (s | v) | replace(' ', 'x') %}"]
    assets += _mesh_assets(shape, scaled=True)
    assets.append("{% endfor %}")
    files[f"{folder}/assets.xml.j2"] = _text(assets)
    cls = _class_name(pid.rsplit("/", 1)[-1])
    what = "dynamic" if top.moves else "static"
    doc = (f"{top.name} of {scene.path.name} (Blender {scene.version}), imported by morsec import-blend: a {what} "
           f"object {size[0]:.3g} x {size[1]:.3g} x {size[2]:.3g} m" + (f" of {top.mass:.3g} kg" if top.moves else ""))
    files[f"{folder}/component.py"] = _text([
        f'"""{_py(doc)}. See README.md."""', "", "from morsec.component import Prop", "", "",
        f"class {cls}(Prop):", f'    """{_py(doc)}."""', "",
        f"    short_descr = {json.dumps(f'{top.name} of {scene.path.name}, imported')}",
        f"    defaults = {defaults!r}", "", "",
        f"COMPONENT = {cls}"])
    files[f"{folder}/README.md"] = _text([
        f"# {pid}", "",
        f"`{top.name}` of `{scene.path.name}` (Blender {scene.version}) with its children, imported by "
        f"`morsec import-blend`: {len(shape.visuals)} drawn meshes, {len(shape.colliders)} collision shapes, "
        f"{what}" + (f", {top.mass:.3g} kg" if top.moves else "") + ".", "",
        f"Its frame is the object's (origin and orientation); `size` (default its own extents, "
        f"{size[0]:.3f} x {size[1]:.3f} x {size[2]:.3f} m) scales it, `color` paints the faces of its first material.",
        "", "Regenerate this folder with `morsec import-blend` rather than editing it: see docs/importing-blend.md."])


def _geoms(shape: Shape, ident: str, prefix: str | None, scaled: bool, total: float = 1.0) -> list[str]:
    lines = []
    for visual in shape.visuals:
        mesh = f"{ident}/{visual.mesh}" + ("{{ tag }}" if scaled else "")
        rgba = "{{ color | v }}" if visual.main and scaled else fmt_vec(visual.rgba)
        name = f' name="{prefix}{_attr(visual.mesh)}"' if prefix else ""
        lines.append(f'<geom{name} class="visual" type="mesh" mesh="{mesh}" rgba="{rgba}"/>')
    for i, col in enumerate(shape.colliders):
        name = f' name="{prefix}collision/{i}"' if prefix else ""
        friction = f' friction="{fmt(col.friction)} 0.005 0.0001"'
        share = f"{col.volume / total:.6g}"
        mass = f'{{% if dynamic %}} mass="{{{{ (mass * {share}) | f }}}}"{{% endif %}}' if scaled else ""
        if col.type == "mesh":
            mesh = f"{ident}/collision{i}" + ("{{ tag }}" if scaled else "")
            lines.append(f'<geom{name} class="collision" type="mesh" mesh="{mesh}"{friction}{mass}/>')
            continue
        quat = f' quat="{fmt_vec(col.quat)}"' if not np.allclose(col.quat, [1, 0, 0, 0]) else ""
        if scaled:
            pos = "{{ [" + ", ".join(f"{fmt(v)} * s[{j}]" for j, v in enumerate(col.pos)) + "] | v }}"
            # a scale along the world axes, carried onto the shape's own axes (exact for aligned shapes)
            r = _quat_matrix(col.quat)
            axis_scale = [_axis_scale(r[:, k]) for k in range(3)]
            if col.type == "box":
                size = "{{ [" + ", ".join(f"{fmt(h)} * {a}" for h, a in zip(col.size, axis_scale)) + "] | v }}"
            elif col.type == "sphere":
                size = "{{ (" + fmt(col.size[0]) + " * ((s[0] + s[1] + s[2]) / 3)) | f }}"
            else:
                size = "{{ [" + f"{fmt(col.size[0])} * ({axis_scale[0]} + {axis_scale[1]}) / 2, " \
                    f"{fmt(col.size[1])} * {axis_scale[2]}" + "] | v }}"
        else:
            pos, size = fmt_vec(col.pos), fmt_vec(col.size)
        lines.append(f'<geom{name} class="collision" type="{col.type}" pos="{pos}"{quat} size="{size}"'
                     f'{friction}{mass}/>')
    return lines


def _axis_scale(axis: np.ndarray) -> str:
    """How much the scale `s` (along the prop's axes) stretches a shape's own axis (a unit vector)."""
    terms = [(j, float(v)) for j, v in enumerate(axis) if abs(v) > 1e-9]
    if len(terms) == 1 and abs(abs(terms[0][1]) - 1) < 1e-9:
        return f"s[{terms[0][0]}]"
    return "((" + " + ".join(f"({fmt(v)} * s[{j}]) ** 2" for j, v in terms) + ") ** 0.5)"


def _mesh_assets(shape: Shape, scaled: bool) -> list[str]:
    tag = "{{ tag }}" if scaled else ""
    scale = ' scale="{{ s | v }}"' if scaled else ""
    lines = []
    for visual in shape.visuals:
        lines.append(f'<mesh name="{{{{ id }}}}/{visual.mesh}{tag}" file="{{{{ asset_dir }}}}/{visual.mesh}.stl" '
                     f'inertia="shell"{scale}/>')
    for i, col in enumerate(shape.colliders):
        if col.type == "mesh" and col.points is not None:
            points = " ".join(fmt(float(f"{x:.6g}")) for x in col.points.ravel())
            lines.append(f'<mesh name="{{{{ id }}}}/collision{i}{tag}" vertex="{points}"{scale}/>')
    return lines


def _lights(world: list[BlendObject]) -> list[str]:
    lines = []
    for obj in world:
        lamp = obj.lamp
        if lamp is None or len(lines) >= MAX_LIGHTS:
            continue
        pos = obj.matrix[:3, 3]
        direction = -obj.matrix[:3, 2] / max(np.linalg.norm(obj.matrix[:3, 2]), 1e-9)
        diffuse = np.clip(np.asarray(lamp.color) * lamp.energy, 0, 1)
        name = _attr("light/" + obj.name)
        if lamp.kind in ("sun", "hemi"):
            lines.append(f'<light name="{name}" pos="{fmt_vec(pos)}" dir="{fmt_vec(direction)}" directional="true" '
                         f'diffuse="{fmt_vec(diffuse * 0.8)}" specular="0.1 0.1 0.1" castshadow="true"/>')
        else:
            # MuJoCo's lights are spots: a cutoff of 180 degrees makes a point lamp (as OpenGL's)
            spread = np.degrees(lamp.spot_angle) / 2 if lamp.kind == "spot" else 180.0
            cutoff = f' cutoff="{fmt(spread)}" exponent="{1 if lamp.kind == "spot" else 0}"'
            attenuation = f"1 {fmt(1 / max(lamp.distance, 1e-3))} 0"
            lines.append(f'<light name="{name}" pos="{fmt_vec(pos)}" dir="{fmt_vec(direction)}" '
                         f'diffuse="{fmt_vec(diffuse * 0.6)}" specular="0 0 0" attenuation="{attenuation}"{cutoff} '
                         'castshadow="false"/>')
    return lines


def _quat_matrix(q: np.ndarray) -> np.ndarray:
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _bounds(shape: Shape) -> tuple[np.ndarray, np.ndarray]:
    """Extents of what a prop draws (else of what it collides with), in its frame."""
    points = []
    for name in shape.files:
        data = shape.files[name]
        count = struct.unpack_from("<I", data, 80)[0]
        record = np.frombuffer(data, dtype=[("n", "<f4", (3,)), ("v", "<f4", (3, 3)), ("a", "<u2")], count=count,
                               offset=84)
        points.append(record["v"].reshape(-1, 3).astype(float))
    if not points:
        for col in shape.colliders:
            if col.points is not None:
                points.append(col.points)
            else:
                points.append(col.pos + np.array([[-1, -1, -1], [1, 1, 1]]) * max(col.size))
    stacked = np.concatenate(points) if points else np.zeros((1, 3))
    return stacked.min(axis=0), stacked.max(axis=0)


def _extents(objects: list[BlendObject]) -> tuple[list[float], list[float]]:
    points = [o.mesh.vertices @ o.matrix[:3, :3].T + o.matrix[:3, 3] for o in objects
              if o.mesh is not None and len(o.mesh.vertices) and not o.invisible]
    if not points:
        return [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    stacked = np.concatenate(points)
    return _vec(stacked.min(axis=0)), _vec(stacked.max(axis=0))


def _write(root: Path, files: dict[str, bytes], targets: list[str], replace: bool) -> None:
    existing = [t for t in targets if (root / t).exists()]
    if existing and not replace:
        raise ImportFailure(f"{', '.join(str(root / t) for t in existing)} already exist(s): --force replaces")
    staging = root / f".import-{os.getpid()}"
    try:
        for name, data in files.items():
            path = staging / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(data)
        for target in targets:
            final = root / target
            final.parent.mkdir(parents=True, exist_ok=True)
            if final.exists():
                shutil.rmtree(final)
            (staging / target).rename(final)
    except OSError as err:
        raise ImportFailure(f"cannot write under {root}: {err.strerror or err}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)


# ---- small helpers

def _scene_name(name: str) -> str:
    """A Blender name as a scene's object name: '.' (Blender's "Chair.001"), spaces and slashes cannot be in it."""
    return "".join("_" if c in FORBIDDEN_NAME_CHARS or not c.isprintable() else c for c in name)


def _unique(name: str, taken: set[str]) -> str:
    candidate, n = name, 1
    while candidate.lower() in taken:
        n += 1
        candidate = f"{name}_{n}"
    taken.add(candidate.lower())
    return candidate


def _names(names: list[str]) -> str:
    return ", ".join(f"`{n}`" for n in names) or "none"


def _class_name(ident: str) -> str:
    words = re.split(r"[^A-Za-z0-9]+", ident.rsplit("/", 1)[-1])
    name = "".join(w[:1].upper() + w[1:] for w in words if w) or "Imported"
    return name if name[0].isalpha() else "Imported" + name


def _vec(values) -> list[float]:
    return [float(f"{float(v):.6g}") + 0.0 for v in values]


def _text(lines: list[str]) -> bytes:
    return ("\n".join(lines) + "\n").encode("utf-8")


def _py(text: str) -> str:
    return text.replace("\\", "\\\\").replace('"""', "'''")


def _comment(text: str) -> str:
    return text.replace("--", "- -").replace("{", "(").replace("}", ")")


def _attr(text: str) -> str:
    return text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;").replace("{", "(").replace("}", ")")
