"""What a MORSE environment or props file holds, read from its blocks (morsec.kits.blend.sdna): objects with
their names, parents, world matrices, game-engine physics and game properties; meshes as triangles with a
material slot each; materials' colours and friction; lamps. Written for the files of Blender 2.5x to 2.7x
(MORSE's), which keep the game engine's settings; a layout this reader does not know is refused with why.

Modifiers are applied where they change the shape a robot meets (Mirror, Array); those that only smooth or
round a mesh (Subsurf, Bevel, EdgeSplit ...) leave the base mesh, and the import says so. Instances of a group
(Blender's "dupli group") are expanded into their objects."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from morsec.kits.blend.sdna import BlendFile, BlendFormatError, Struct

OBJECT_KINDS = {0: "empty", 1: "mesh", 2: "curve", 3: "surface", 4: "text", 5: "metaball", 10: "lamp",
                11: "camera", 12: "speaker", 22: "lattice", 25: "armature"}
# ob->gameflag bits (DNA_object_types.h of Blender 2.6x)
OB_DYNAMIC, OB_CHILD, OB_ACTOR, OB_GHOST, OB_RIGID_BODY, OB_BOUNDS = 0x1, 0x2, 0x4, 0x200, 0x400, 0x800
OB_COLLISION, OB_SOFT_BODY, OB_OCCLUDER, OB_SENSOR, OB_NAVMESH, OB_CHARACTER = (0x10000, 0x20000, 0x40000,
                                                                              0x80000, 0x100000, 0x400000)
OB_RESTRICT_RENDER = 4  # the game engine's "Invisible" (ob->restrictflag)
OB_DUPLIGROUP = 0x100  # ob->transflag
BOUNDS = {0: "box", 1: "sphere", 2: "cylinder", 3: "cone", 4: "triangle_mesh", 5: "convex_hull", 6: "triangle_mesh",
          7: "capsule"}
PROPERTY_TYPES = {0: bool, 1: int, 2: float, 3: str, 5: float}  # bProperty.type: BOOL INT FLOAT STRING TIME
LAMP_TYPES = {0: "point", 1: "sun", 2: "spot", 3: "hemi", 4: "area"}
# modifiers that round or smooth a mesh, or only change its normals or triangulation: the base mesh stands in
SHAPE_PRESERVING = {"Subsurf", "Multires", "Bevel", "EdgeSplit", "Smooth", "LaplacianSmooth", "Triangulate",
                    "Decimate", "Remesh", "WeightedNormal", "UVProject", "UVWarp"}
MIRROR_AXES = {0x8: 0, 0x10: 1, 0x20: 2}
ARRAY_CONST, ARRAY_RELATIVE, ARRAY_OBJECT = 1, 2, 4
MAX_GROUP_DEPTH = 8


@dataclass
class Material:
    name: str
    color: tuple[float, float, float, float]  # diffuse RGB and alpha, 0..1
    friction: float | None  # the game engine's material friction (Blender 2.6x: Material.friction)


@dataclass
class Mesh:
    vertices: np.ndarray  # (n, 3) float64, in the object's own frame (scale not applied)
    triangles: np.ndarray  # (m, 3) int, vertex indices, counter-clockwise seen from the outside
    slots: np.ndarray  # (m,) int, each triangle's material slot


@dataclass
class Lamp:
    kind: str  # point, sun, spot, hemi, area
    color: tuple[float, float, float]
    energy: float
    distance: float
    spot_angle: float  # full cone angle, rad (spot lamps)


@dataclass(eq=False)  # identity: objects are keys of the importer's tables
class BlendObject:
    name: str
    kind: str  # mesh, empty, lamp, camera, curve, ...
    parent: str | None
    matrix: np.ndarray  # 4x4, world frame, as Blender last evaluated it (obmat)
    layers: int
    invisible: bool  # the game engine does not draw it (collision proxies are invisible)
    physics: str  # no_collision, static, dynamic, rigid_body, soft_body, sensor, occluder, navmesh, character
    ghost: bool
    compound: bool  # its children's shapes are part of its own (Blender's "Compound")
    bounds: str  # box, sphere, cylinder, cone, capsule, convex_hull, triangle_mesh
    bounds_set: bool  # Collision Bounds ticked (else the game engine's default shape)
    mass: float
    radius: float  # the game engine's "Radius": a dynamic object's sphere when no bounds are set
    damping: float
    rotation_damping: float
    properties: dict[str, bool | int | float | str]  # game properties, in the file's order
    custom: dict[str, object]  # ID properties (Blender's custom properties)
    mesh: Mesh | None = None
    materials: list[Material | None] = field(default_factory=list)  # per slot
    lamp: Lamp | None = None
    notes: list[str] = field(default_factory=list)  # what was approximated (modifiers left out ...)

    @property
    def collides(self) -> bool:
        return self.physics not in ("no_collision", "sensor", "occluder", "navmesh") and not self.ghost

    @property
    def moves(self) -> bool:
        return self.physics in ("dynamic", "rigid_body", "soft_body", "character")


@dataclass
class BlendScene:
    path: Path
    version: str  # "2.61"
    scene: str  # the scene the objects come from
    objects: list[BlendObject]

    def by_name(self) -> dict[str, BlendObject]:
        return {o.name: o for o in self.objects}

    def children(self, name: str) -> list[BlendObject]:
        return [o for o in self.objects if o.parent == name]


def read_blend(path: Path, every_layer: bool = False) -> BlendScene:
    """The objects of the scene the file was saved in (`every_layer`: all its objects, as MORSE's
    PassiveObject takes a props file's objects whatever layer holds them; else those on the scene's visible
    layers, which are the ones Blender's game engine showed)."""
    file = BlendFile(path)
    reader = _Reader(file)
    return reader.scene(every_layer)


class _Reader:
    def __init__(self, file: BlendFile):
        self.file = file
        self.libraries = {b.address for b in file.of_code(b"LI\0\0")}
        self.materials: dict[int, Material | None] = {}

    def scene(self, every_layer: bool) -> BlendScene:
        file = self.file
        scenes = file.of_code(b"SC\0\0")
        if not scenes:
            raise BlendFormatError("it holds no scene")
        chosen = scenes[0]
        globs = file.of_code(b"GLOB")
        if globs:
            current = file.at(globs[0]).get("curscene", 0)
            chosen = next((b for b in scenes if b.address == current), chosen)
        scene = file.at(chosen)
        visible = scene["lay"]
        if every_layer:
            bases = [file.at(b) for b in file.of_code(b"OB\0\0")]
        else:
            bases = []
            for base in file.listbase(scene["base"]["first"], "Base"):
                ob = file.deref(base["object"], "Object")
                if ob is not None and ob["lay"] & visible:
                    bases.append(ob)
        objects: list[BlendObject] = []
        for ob in bases:
            self._check_local(ob, "object")
            obj = self._object(ob, np.eye(4), None, "")
            objects.append(obj)
            if ob["transflag"] & OB_DUPLIGROUP and ob["dup_group"]:
                objects.extend(self._group_instance(ob, obj, 1))
        names = [o.name for o in objects]
        if len(set(names)) != len(names):
            raise BlendFormatError("two objects share a name (a group instanced twice?)")
        version = f"{file.version // 100}.{file.version % 100:02d}"
        return BlendScene(file.path, version, scene["id"]["name"][2:], objects)

    def _check_local(self, struct: Struct, what: str) -> None:
        ident = struct if struct.name == "ID" else struct["id"]  # data linked from a library is an ID block
        if ident["lib"]:
            library = self.file.deref(ident["lib"], "Library")
            where = library["name"] if library is not None else "another file"
            raise BlendFormatError(f"its {what} {ident['name'][2:]!r} is linked from the library {where}: make it "
                                   "local in Blender (Object > Relations > Make Local > All) and save, then import")

    def _group_instance(self, holder: Struct, holder_obj: BlendObject, depth: int) -> list[BlendObject]:
        """The objects of the group an empty instances, placed by the empty: Blender draws group member m at
        holder.obmat @ translate(-group.dupli_ofs) @ m.obmat."""
        if depth > MAX_GROUP_DEPTH:
            raise BlendFormatError(f"object {holder_obj.name!r} instances groups more than {MAX_GROUP_DEPTH} deep")
        group = self.file.deref(holder["dup_group"])
        if group is None:
            return []
        self._check_local(group, "group")
        offset = np.eye(4)
        offset[:3, 3] = -np.asarray(group.get("dupli_ofs", np.zeros(3)), float)
        place = holder_obj.matrix @ offset
        members = []
        for item in self.file.listbase(group["gobject"]["first"], "GroupObject"):
            ob = self.file.deref(item["ob"], "Object")
            if ob is None:
                continue
            self._check_local(ob, "object")
            member = self._object(ob, place, holder_obj.name, holder_obj.name + "/")
            members.append(member)
            if ob["transflag"] & OB_DUPLIGROUP and ob["dup_group"]:
                members.extend(self._group_instance(ob, member, depth + 1))
        names = {m.name for m in members}
        for m in members:  # inside the group, parents keep their instanced names
            if m.parent is None or m.parent not in names and m.parent != holder_obj.name:
                prefixed = holder_obj.name + "/" + m.parent if m.parent else None
                m.parent = prefixed if prefixed in names else holder_obj.name
        return members

    def _object(self, ob: Struct, place: np.ndarray, instance_of: str | None, prefix: str) -> BlendObject:
        file = self.file
        name = ob["id"]["name"][2:]
        parent = file.deref(ob["parent"], "Object")
        parent_name = prefix + parent["id"]["name"][2:] if parent is not None else instance_of
        matrix = place @ np.asarray(ob["obmat"], float).T
        flags = ob["gameflag"]
        bound_field = "collision_boundtype" if ob.has("collision_boundtype") else "boundtype"
        obj = BlendObject(
            name=prefix + name, kind=OBJECT_KINDS.get(ob["type"], f"type {ob['type']}"), parent=parent_name,
            matrix=matrix, layers=ob["lay"], invisible=bool(ob["restrictflag"] & OB_RESTRICT_RENDER),
            physics=_physics(flags), ghost=bool(flags & OB_GHOST), compound=bool(flags & OB_CHILD),
            bounds=_bounds(flags, ob[bound_field]), bounds_set=bool(flags & OB_BOUNDS), mass=float(ob["mass"]),
            radius=float(ob["inertia"]),
            damping=float(ob["damping"]), rotation_damping=float(ob["rdamping"]),
            properties=self._game_properties(ob), custom=self._id_properties(ob["id"]))
        if obj.kind == "mesh":
            data = file.deref(ob["data"], "Mesh")
            if data is None:
                raise BlendFormatError(f"object {name!r}: its mesh is missing from the file")
            self._check_local(data, "mesh")
            obj.mesh = self._mesh(data, name)
            obj.materials = self._slots(ob, data)
            self._modifiers(ob, obj)
        elif obj.kind == "lamp":
            lamp = file.deref(ob["data"], "Lamp")
            if lamp is not None:
                obj.lamp = Lamp(LAMP_TYPES.get(lamp["type"], "point"), (lamp["r"], lamp["g"], lamp["b"]),
                                float(lamp["energy"]), float(lamp["dist"]), float(np.radians(lamp["spotsize"]))
                                if lamp["spotsize"] > 3.2 else float(lamp["spotsize"]))
        return obj

    # ---- meshes

    def _mesh(self, me: Struct, name: str) -> Mesh:
        file = self.file
        nvert = me["totvert"]
        if nvert and not me.get("mvert"):
            raise BlendFormatError(f"mesh of {name!r} keeps its vertices as attributes (Blender 3.5 or later): "
                                   "this reader reads the files of Blender 2.5 to 3.4")
        co = file.array(me["mvert"], "MVert", ("co",))["co"].reshape(-1, 3).astype(float) if nvert else \
            np.zeros((0, 3))
        tris: list[np.ndarray] = []
        slots: list[np.ndarray] = []
        if me.get("totpoly", 0):
            polys = file.array(me["mpoly"], "MPoly", ("loopstart", "totloop", "mat_nr"))
            loops = file.array(me["mloop"], "MLoop", ("v",))["v"].astype(np.int64)
            for n in np.unique(polys["totloop"]):
                if n < 3:
                    continue
                pick = polys["totloop"] == n
                starts = polys["loopstart"][pick].astype(np.int64)
                corners = loops[starts[:, None] + np.arange(n)[None, :]]
                for k in range(1, n - 1):  # a fan from each polygon's first corner
                    tris.append(corners[:, [0, k, k + 1]])
                    slots.append(polys["mat_nr"][pick].astype(np.int64))
        elif me.get("totface", 0):
            faces = file.array(me["mface"], "MFace", ("v1", "v2", "v3", "v4", "mat_nr"))
            v = np.stack([faces["v1"], faces["v2"], faces["v3"], faces["v4"]], axis=1).astype(np.int64)
            tris.append(v[:, [0, 1, 2]])
            slots.append(faces["mat_nr"].astype(np.int64))
            quads = faces["v4"] != 0
            tris.append(v[quads][:, [0, 2, 3]])
            slots.append(faces["mat_nr"][quads].astype(np.int64))
        triangles = np.concatenate(tris) if tris else np.zeros((0, 3), np.int64)
        slot = np.concatenate(slots) if slots else np.zeros((0,), np.int64)
        if len(triangles) and (triangles.max() >= len(co) or triangles.min() < 0):
            raise BlendFormatError(f"mesh of {name!r} has faces naming vertices it does not have (damaged file)")
        return Mesh(co, triangles, slot)

    def _slots(self, ob: Struct, me: Struct) -> list[Material | None]:
        """Material per slot: the object's own where its slot says so (matbits), else the mesh's."""
        file = self.file
        mesh_mats = file.pointers(me["mat"]) if me["mat"] else []
        ob_mats = file.pointers(ob["mat"]) if ob["mat"] else []
        bits_block = file.block_at(ob["matbits"]) if ob["matbits"] else None
        bits = list(file.raw[bits_block.start:bits_block.start + bits_block.size]) if bits_block else []
        count = max(me["totcol"], ob["totcol"])
        out: list[Material | None] = []
        for i in range(count):
            own = i < len(bits) and bits[i] and i < len(ob_mats)
            address = ob_mats[i] if own else (mesh_mats[i] if i < len(mesh_mats) else 0)
            out.append(self._material(address))
        return out

    def _material(self, address: int) -> Material | None:
        if not address:
            return None
        if address not in self.materials:
            ma = self.file.deref(address, "Material")
            if ma is None:
                self.materials[address] = None
            else:
                self._check_local(ma, "material")
                self.materials[address] = Material(
                    ma["id"]["name"][2:], (float(ma["r"]), float(ma["g"]), float(ma["b"]), float(ma["alpha"])),
                    float(ma["friction"]) if ma.has("friction") else None)
        return self.materials[address]

    def _modifiers(self, ob: Struct, obj: BlendObject) -> None:
        assert obj.mesh is not None
        for mod in self.file.listbase(ob["modifiers"]["first"]):
            kind = mod.name.removesuffix("ModifierData")
            if not mod["modifier"]["mode"] & 1:  # not enabled for the viewport and game
                continue
            if kind == "Mirror":
                obj.mesh = self._mirror(mod, obj)
            elif kind == "Array":
                obj.mesh = self._array(mod, obj)
            elif kind in SHAPE_PRESERVING:
                obj.notes.append(f"{kind} modifier: drawn from its base mesh")
            else:
                obj.notes.append(f"{kind} modifier not applied (its base mesh is imported)")

    def _mirror(self, mod: Struct, obj: BlendObject) -> Mesh:
        mesh = obj.mesh
        assert mesh is not None
        flag = mod["flag"]
        axes = [axis for bit, axis in MIRROR_AXES.items() if flag & bit]
        frame = np.eye(4)  # the mirror plane's frame, in the object's: its own, or the mirror object's
        if mod.get("mirror_ob"):
            other = self.file.deref(mod["mirror_ob"], "Object")
            if other is not None:
                own = obj.matrix
                frame = np.linalg.inv(own) @ np.asarray(other["obmat"], float).T
        inverse = np.linalg.inv(frame)
        for axis in axes:
            flip = np.eye(4)
            flip[axis, axis] = -1.0
            reflect = frame @ flip @ inverse
            mirrored = mesh.vertices @ reflect[:3, :3].T + reflect[:3, 3]
            n = len(mesh.vertices)
            # a reflection turns faces inside out: reverse the corners' order to keep them facing outwards
            mesh = Mesh(np.concatenate([mesh.vertices, mirrored]),
                        np.concatenate([mesh.triangles, mesh.triangles[:, ::-1] + n]),
                        np.concatenate([mesh.slots, mesh.slots]))
        return mesh

    def _array(self, mod: Struct, obj: BlendObject) -> Mesh:
        mesh = obj.mesh
        assert mesh is not None
        step = np.zeros(3)
        kind = mod["offset_type"]
        if kind & ARRAY_CONST:
            step += np.asarray(mod["offset"], float)
        if kind & ARRAY_RELATIVE and len(mesh.vertices):
            step += np.asarray(mod["scale"], float) * (mesh.vertices.max(0) - mesh.vertices.min(0))
        if kind & ARRAY_OBJECT and mod["offset_ob"]:
            obj.notes.append("Array modifier: its offset object is not applied")
        count = int(mod["count"])
        if mod["fit_type"] == 1:  # fit a length
            length = float(np.linalg.norm(step))
            count = int(mod["length"] / length + 1e-6) + 1 if length > 0 else 1
        elif mod["fit_type"] == 2:
            obj.notes.append("Array modifier: fitted to a curve in Blender, imported with its count")
        if mod.get("start_cap") or mod.get("end_cap"):
            obj.notes.append("Array modifier: its caps are not imported")
        count = max(1, min(count, 1000))
        n = len(mesh.vertices)
        return Mesh(np.concatenate([mesh.vertices + i * step for i in range(count)]),
                    np.concatenate([mesh.triangles + i * n for i in range(count)]),
                    np.concatenate([mesh.slots] * count))

    # ---- properties

    def _game_properties(self, ob: Struct) -> dict[str, bool | int | float | str]:
        out: dict[str, bool | int | float | str] = {}
        for prop in self.file.listbase(ob["prop"]["first"], "bProperty"):
            kind = PROPERTY_TYPES.get(prop["type"])
            if kind is None:
                continue
            data = prop["data"]
            if kind is bool:
                out[prop["name"]] = bool(data)
            elif kind is int:
                out[prop["name"]] = int(data)
            elif kind is float:  # the float's bits are kept in the int `data`
                out[prop["name"]] = float(np.array([data], np.int32).view(np.float32)[0])
            else:
                out[prop["name"]] = self.file.string_at(prop["poin"])
        return out

    def _id_properties(self, ident: Struct) -> dict[str, object]:
        group = self.file.deref(ident.get("properties", 0), "IDProperty")
        if group is None:
            return {}
        return self._id_group(group, 0)

    def _id_group(self, group: Struct, depth: int) -> dict[str, object]:
        out: dict[str, object] = {}
        if depth > 8:
            return out
        for prop in self.file.listbase(group["data"]["group"]["first"], "IDProperty"):
            value = self._id_value(prop, depth)
            if value is not None and not prop["name"].startswith("_"):
                out[prop["name"]] = value
        return out

    def _id_value(self, prop: Struct, depth: int):
        kind, data = prop["type"], prop["data"]
        if kind == 0:  # string
            return self.file.string_at(data["pointer"])
        if kind == 1:
            return int(data["val"])
        if kind == 2:
            return float(np.array([data["val"]], np.int32).view(np.float32)[0])
        if kind == 7:  # double, in val and val2
            return float(np.array([data["val"], data["val2"]], np.int32).view(np.float64)[0])
        if kind == 5:
            return self._id_group(prop, depth + 1)
        return None  # arrays, ID pointers: not a value a scene's property bag holds


def _physics(flags: int) -> str:
    """The game engine's physics type from the object's flags, as Blender 2.6x's own getter derives it."""
    if not flags & OB_COLLISION:
        if flags & OB_OCCLUDER:
            return "occluder"
        return "navmesh" if flags & OB_NAVMESH else "no_collision"
    if flags & OB_SENSOR:
        return "sensor"
    if flags & OB_CHARACTER:
        return "character"
    if not flags & OB_DYNAMIC:
        return "static"
    if flags & OB_RIGID_BODY:
        return "rigid_body"
    return "soft_body" if flags & OB_SOFT_BODY else "dynamic"


def _bounds(flags: int, boundtype: int) -> str:
    """The collision shape: the one chosen when Collision Bounds is ticked, else the game engine's default (a
    sphere of the object's Radius for what moves, its triangles for the rest)."""
    if flags & OB_BOUNDS:
        return BOUNDS.get(boundtype, "convex_hull")
    return "sphere" if flags & OB_DYNAMIC else "triangle_mesh"
