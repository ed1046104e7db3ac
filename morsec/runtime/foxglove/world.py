"""What Foxglove's 3D panel draws of a MuJoCo model: every body as a frame of one transform tree (named as
the MJCF names it: the world body `world`, a robot by its name, a component by its full name, a link
`robot/link`; its parent frame the body it hangs from), and the geoms MuJoCo's viewer shows (groups 0 to
2) as primitives locked to their body's frame: boxes, spheres, cylinders, capsules (a cylinder and two
spheres), ellipsoids, planes (a thin box) and meshes (binary STL, bounding box beyond MESH_FACES)."""

from __future__ import annotations

import struct

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


def geom_color(model, g: int) -> Color:
    rgba = tuple(float(v) for v in model.geom_rgba[g])
    matid = int(model.geom_matid[g])
    if matid >= 0 and np.allclose(rgba, DEFAULT_RGBA):
        rgba = tuple(float(v) for v in model.mat_rgba[matid])
    return Color(r=rgba[0], g=rgba[1], b=rgba[2], a=rgba[3])


def _pose(pos, quat) -> Pose:
    return Pose(position=Vector3(x=float(pos[0]), y=float(pos[1]), z=float(pos[2])),
                orientation=Quaternion(x=float(quat[1]), y=float(quat[2]), z=float(quat[3]), w=float(quat[0])))


def _shifted(pos, quat, along_z: float) -> np.ndarray:
    """A point `along_z` on the geom's own z axis, in its body's frame."""
    w, x, y, z = quat
    axis = np.array([2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)])
    return np.asarray(pos) + along_z * axis


def stl(vertices: np.ndarray, faces: np.ndarray) -> bytes:
    """Binary STL of a triangle mesh (normals left to the reader: zero, as STL allows)."""
    triangles = np.zeros(len(faces), dtype=[("normal", "<f4", 3), ("points", "<f4", (3, 3)), ("attr", "<u2")])
    triangles["points"] = vertices[faces]
    return b"morsec mesh".ljust(80, b" ") + struct.pack("<I", len(faces)) + triangles.tobytes()


class Primitives:
    """The primitives of one body's entity."""

    def __init__(self):
        self.cubes: list = []
        self.spheres: list = []
        self.cylinders: list = []
        self.models: list = []

    def __bool__(self) -> bool:
        return bool(self.cubes or self.spheres or self.cylinders or self.models)


def add_geom(model, g: int, into: Primitives) -> None:
    kind = int(model.geom_type[g])
    size = model.geom_size[g]
    pos, quat = model.geom_pos[g], model.geom_quat[g]
    color = geom_color(model, g)
    G = mujoco.mjtGeom
    if kind == G.mjGEOM_BOX:
        into.cubes.append(CubePrimitive(pose=_pose(pos, quat), size=Vector3(x=2 * size[0], y=2 * size[1],
                                                                             z=2 * size[2]), color=color))
    elif kind == G.mjGEOM_SPHERE:
        d = 2 * float(size[0])
        into.spheres.append(SpherePrimitive(pose=_pose(pos, quat), size=Vector3(x=d, y=d, z=d), color=color))
    elif kind == G.mjGEOM_ELLIPSOID:
        into.spheres.append(SpherePrimitive(pose=_pose(pos, quat), size=Vector3(x=2 * size[0], y=2 * size[1],
                                                                                 z=2 * size[2]), color=color))
    elif kind == G.mjGEOM_CYLINDER:
        d = 2 * float(size[0])
        into.cylinders.append(CylinderPrimitive(pose=_pose(pos, quat), size=Vector3(x=d, y=d, z=2 * size[1]),
                                                bottom_scale=1.0, top_scale=1.0, color=color))
    elif kind == G.mjGEOM_CAPSULE:
        d, half = 2 * float(size[0]), float(size[1])
        into.cylinders.append(CylinderPrimitive(pose=_pose(pos, quat), size=Vector3(x=d, y=d, z=2 * half),
                                                bottom_scale=1.0, top_scale=1.0, color=color))
        for end in (-half, half):
            into.spheres.append(SpherePrimitive(pose=_pose(_shifted(pos, quat, end), quat),
                                                size=Vector3(x=d, y=d, z=d), color=color))
    elif kind == G.mjGEOM_PLANE:
        sx, sy = (2 * float(s) if s > 0 else PLANE_SIZE for s in size[:2])
        into.cubes.append(CubePrimitive(pose=_pose(_shifted(pos, quat, -PLANE_THICKNESS / 2), quat),
                                        size=Vector3(x=sx, y=sy, z=PLANE_THICKNESS), color=color))
    elif kind == G.mjGEOM_MESH:
        mesh = int(model.geom_dataid[g])
        faces = int(model.mesh_facenum[mesh])
        if faces > MESH_FACES:  # its bounding box in the geom's frame
            centre, half = model.geom_aabb[g][:3], model.geom_aabb[g][3:]
            into.cubes.append(CubePrimitive(pose=_pose(np.asarray(pos) + _rotate(quat, centre), quat),
                                            size=Vector3(x=2 * half[0], y=2 * half[1], z=2 * half[2]), color=color))
            return
        v0, f0 = int(model.mesh_vertadr[mesh]), int(model.mesh_faceadr[mesh])
        vertices = model.mesh_vert[v0:v0 + int(model.mesh_vertnum[mesh])]
        into.models.append(ModelPrimitive(pose=_pose(pos, quat), scale=Vector3(x=1.0, y=1.0, z=1.0), color=color,
                                          override_color=True, media_type="model/stl",
                                          data=stl(vertices, model.mesh_face[f0:f0 + faces])))
    # height fields and SDFs are not drawn


def _rotate(quat, v) -> np.ndarray:
    out = np.zeros(3)
    mujoco.mju_rotVecQuat(out, np.asarray(v, float), np.asarray(quat, float))
    return out


class SceneGeometry:
    """One entity per body that has visible geoms, in that body's frame and locked to it (it moves with the
    body's transform); its primitives made once (meshes are the costly part)."""

    def __init__(self, model):
        names = frame_names(model)
        bodies: dict[int, Primitives] = {}
        for g in range(model.ngeom):
            if model.geom_group[g] < VISIBLE_GROUPS and model.geom_rgba[g][3] > 0:
                add_geom(model, g, bodies.setdefault(int(model.geom_bodyid[g]), Primitives()))
        self.bodies = [(names[b], p) for b, p in sorted(bodies.items()) if p]

    def message(self, seconds: float) -> SceneUpdate:
        when = stamp(seconds)
        return SceneUpdate(entities=[
            SceneEntity(timestamp=when, frame_id=name, id=name, frame_locked=True, cubes=p.cubes,
                        spheres=p.spheres, cylinders=p.cylinders, models=p.models)
            for name, p in self.bodies])
