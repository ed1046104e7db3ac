"""What Foxglove's 3D panel draws of a MuJoCo model: every body as a frame of one transform tree (named as
the MJCF names it: the world body `world`, a robot by its name, a component by its full name, a link
`robot/link`; its parent frame the body it hangs from), and the geoms MuJoCo's viewer shows (groups 0 to
2) as primitives locked to their body's frame: boxes, spheres, cylinders, capsules (a cylinder and two
spheres), ellipsoids, planes (a thin box) and meshes (binary STL, bounding box beyond MESH_FACES)."""

from __future__ import annotations

import struct
from dataclasses import dataclass

import mujoco
import numpy as np
from foxglove.messages import (
    Color,
    CubePrimitive,
    CylinderPrimitive,
    FrameTransform,
    FrameTransforms,
    ModelPrimitive,
    Pose,
    Quaternion,
    SceneEntity,
    SceneUpdate,
    SpherePrimitive,
    Timestamp,
    Vector3,
)

WORLD_FRAME = "world"
VISIBLE_GROUPS = 3  # geom groups 0, 1, 2: what MuJoCo's viewer draws (3 is collision-only, 5 sites and helpers)
PLANE_SIZE = 100.0  # m: the side of an infinite MuJoCo plane as drawn
PLANE_THICKNESS = 0.001  # m
MESH_FACES = 50_000  # a mesh with more triangles than this is drawn as its bounding box
DEFAULT_RGBA = (0.5, 0.5, 0.5, 1.0)  # MuJoCo's geom colour: a geom with a material and this colour takes the material's


def stamp(seconds: float) -> Timestamp:
    sec = int(seconds // 1)
    return Timestamp(sec=sec, nsec=min(int(round((seconds - sec) * 1e9)), 999_999_999))


def frame_names(model) -> list[str]:
    return [WORLD_FRAME if b == 0 else (model.body(b).name or f"body{b}") for b in range(model.nbody)]


class BodyFrames:
    """The transform of every body in its parent's frame, from MjData's world poses: one vectorized
    computation per message, whatever the number of bodies."""

    def __init__(self, model):
        self.names = frame_names(model)
        self.child = np.arange(1, model.nbody)
        self.parent = np.asarray(model.body_parentid[1:])

    def relative(self, data) -> tuple[np.ndarray, np.ndarray]:
        """(translations n x 3, quaternions n x 4 as w, x, y, z) of each body in its parent's frame."""
        xpos, xquat, xmat = data.xpos, data.xquat, data.xmat
        rot = xmat[self.parent].reshape(-1, 3, 3)  # world from parent
        offset = xpos[self.child] - xpos[self.parent]
        translation = np.einsum("nji,nj->ni", rot, offset)  # parent from world, applied to the offset
        a = xquat[self.parent] * np.array([1.0, -1.0, -1.0, -1.0])  # the parent's inverse
        b = xquat[self.child]
        aw, ax, ay, az = a.T
        bw, bx, by, bz = b.T
        rotation = np.column_stack((aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                                    aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw))
        return translation, rotation

    def message(self, data, seconds: float) -> FrameTransforms:
        translation, rotation = self.relative(data)
        when = stamp(seconds)
        names, parent = self.names, self.parent.tolist()
        return FrameTransforms(transforms=[
            FrameTransform(timestamp=when, parent_frame_id=names[p], child_frame_id=names[c],
                           translation=Vector3(x=t[0], y=t[1], z=t[2]),
                           rotation=Quaternion(x=q[1], y=q[2], z=q[3], w=q[0]))
            for c, p, t, q in zip(self.child.tolist(), parent, translation.tolist(), rotation.tolist())])


@dataclass(frozen=True)
class Shape:
    """One primitive of a body's entity, in the body's frame: a cube, sphere or cylinder of `size` (full
    extents, m; a cylinder's axis is its z), or a model (`data`: binary STL)."""

    kind: str  # "cube" | "sphere" | "cylinder" | "model"
    position: tuple[float, float, float]
    quat: tuple[float, float, float, float]  # w, x, y, z
    size: tuple[float, float, float]
    rgba: tuple[float, float, float, float]
    data: bytes = b""


def geom_rgba(model, g: int) -> tuple[float, float, float, float]:
    rgba = tuple(float(v) for v in model.geom_rgba[g])
    matid = int(model.geom_matid[g])
    if matid >= 0 and np.allclose(rgba, DEFAULT_RGBA):
        rgba = tuple(float(v) for v in model.mat_rgba[matid])
    return rgba  # type: ignore[return-value]


def _shifted(pos, quat, along_z: float) -> np.ndarray:
    """A point `along_z` on the geom's own z axis, in its body's frame."""
    return np.asarray(pos, float) + _rotate(quat, (0.0, 0.0, along_z))


def _rotate(quat, v) -> np.ndarray:
    out = np.zeros(3)
    mujoco.mju_rotVecQuat(out, np.asarray(v, float), np.asarray(quat, float))
    return out


def stl(vertices: np.ndarray, faces: np.ndarray) -> bytes:
    """Binary STL of a triangle mesh (normals left to the reader: zero, as STL allows)."""
    triangles = np.zeros(len(faces), dtype=[("normal", "<f4", 3), ("points", "<f4", (3, 3)), ("attr", "<u2")])
    triangles["points"] = vertices[faces]
    return b"morsec mesh".ljust(80, b" ") + struct.pack("<I", len(faces)) + triangles.tobytes()


G = mujoco.mjtGeom


def geom_shapes(model, g: int) -> list[Shape]:
    """What geom `g` is drawn as; nothing for a height field or an SDF."""
    kind = int(model.geom_type[g])
    size = [float(v) for v in model.geom_size[g]]
    pos, quat = model.geom_pos[g], model.geom_quat[g]

    def shape(what: str, extents, at=pos, data: bytes = b"") -> Shape:
        return Shape(what, tuple(float(v) for v in at), tuple(float(v) for v in quat),  # type: ignore[arg-type]
                     tuple(float(v) for v in extents), geom_rgba(model, g), data)  # type: ignore[arg-type]

    if kind == G.mjGEOM_BOX:
        return [shape("cube", [2 * v for v in size])]
    if kind == G.mjGEOM_SPHERE:
        return [shape("sphere", [2 * size[0]] * 3)]
    if kind == G.mjGEOM_ELLIPSOID:
        return [shape("sphere", [2 * v for v in size])]
    if kind == G.mjGEOM_CYLINDER:
        return [shape("cylinder", (2 * size[0], 2 * size[0], 2 * size[1]))]
    if kind == G.mjGEOM_CAPSULE:
        d, half = 2 * size[0], size[1]
        return [shape("cylinder", (d, d, 2 * half)),
                *(shape("sphere", (d, d, d), at=_shifted(pos, quat, end)) for end in (-half, half))]
    if kind == G.mjGEOM_PLANE:
        sx, sy = (2 * s if s > 0 else PLANE_SIZE for s in size[:2])
        return [shape("cube", (sx, sy, PLANE_THICKNESS), at=_shifted(pos, quat, -PLANE_THICKNESS / 2))]
    if kind == G.mjGEOM_MESH:
        mesh = int(model.geom_dataid[g])
        faces = int(model.mesh_facenum[mesh])
        if faces > MESH_FACES:  # its bounding box, in the geom's frame
            centre, half_sizes = model.geom_aabb[g][:3], model.geom_aabb[g][3:]
            return [shape("cube", [2 * v for v in half_sizes], at=np.asarray(pos) + _rotate(quat, centre))]
        v0, f0 = int(model.mesh_vertadr[mesh]), int(model.mesh_faceadr[mesh])
        vertices = model.mesh_vert[v0:v0 + int(model.mesh_vertnum[mesh])]
        return [shape("model", (1.0, 1.0, 1.0), data=stl(vertices, model.mesh_face[f0:f0 + faces]))]
    return []


def _primitive(s: Shape):
    pose = Pose(position=Vector3(x=s.position[0], y=s.position[1], z=s.position[2]),
                orientation=Quaternion(x=s.quat[1], y=s.quat[2], z=s.quat[3], w=s.quat[0]))
    size = Vector3(x=s.size[0], y=s.size[1], z=s.size[2])
    color = Color(r=s.rgba[0], g=s.rgba[1], b=s.rgba[2], a=s.rgba[3])
    if s.kind == "cube":
        return CubePrimitive(pose=pose, size=size, color=color)
    if s.kind == "sphere":
        return SpherePrimitive(pose=pose, size=size, color=color)
    if s.kind == "cylinder":
        return CylinderPrimitive(pose=pose, size=size, bottom_scale=1.0, top_scale=1.0, color=color)
    return ModelPrimitive(pose=pose, scale=size, color=color, override_color=True, media_type="model/stl",
                          data=s.data)


class SceneGeometry:
    """One entity per body that has visible geoms, in that body's frame and locked to it (it moves with the
    body's transform); its shapes made once (meshes are the costly part)."""

    def __init__(self, model):
        names = frame_names(model)
        bodies: dict[int, list[Shape]] = {}
        for g in range(model.ngeom):
            if model.geom_group[g] < VISIBLE_GROUPS and model.geom_rgba[g][3] > 0:
                bodies.setdefault(int(model.geom_bodyid[g]), []).extend(geom_shapes(model, g))
        self.bodies = {names[b]: shapes for b, shapes in sorted(bodies.items()) if shapes}

    def message(self, seconds: float) -> SceneUpdate:
        when = stamp(seconds)
        entities = []
        for name, shapes in self.bodies.items():
            kinds: dict[str, list] = {"cube": [], "sphere": [], "cylinder": [], "model": []}
            for s in shapes:
                kinds[s.kind].append(_primitive(s))
            entities.append(SceneEntity(timestamp=when, frame_id=name, id=name, frame_locked=True,
                                        cubes=kinds["cube"], spheres=kinds["sphere"], cylinders=kinds["cylinder"],
                                        models=kinds["model"]))
        return SceneUpdate(entities=entities)
