"""MORSE's SemanticCamera: which tagged objects the camera sees, and where they are. Nothing is rendered:
visibility is geometry (bounding boxes against the view frustum) and one ray per object (occlusion)."""

from __future__ import annotations

import mujoco
import numpy as np
from pydantic import Field

from morsec.component import DataField, Sensor
from morsec.kits.camera import INTRINSIC_MATRIX, OPTICAL_TO_COMPONENT, CameraProperties
from morsec.kits.geometry import matrix_to_quat

SEEN_GROUPS = np.array([1, 1, 1, 0, 0, 0], dtype=np.uint8)  # what a camera renders: geom groups 0-2
HIDDEN_GROUP = 5  # where the carrying robot's geoms are parked while the occlusion rays are cast
NO_EFFECT = "accepted for MORSE scripts, no effect: nothing is rendered"
_SIGNS = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)


class SemanticCamera(Sensor):
    """A "smart" camera reporting the tagged objects it sees: robots and passive objects whose property
    `tag` (default 'Object') is true, or whose `Type` equals `tag`. An object is seen when its bounding
    box (the boxes of its geoms) meets the camera's view frustum (field of view from cam_width,
    cam_height, cam_focal / cam_fov; depth from cam_near to cam_far) and — unless `noocclusion` — a ray
    from the camera to the centre of that bounding box hits that object first. The robot carrying the
    camera neither blocks the view nor is reported. Each seen object: `{name: its Label or name,
    description, type, position: [x, y, z], orientation: {x, y, z, w}}`, in the world frame, or in the
    camera's frame when `relative`: MORSE's camera frame, x right, y down, z forward (the optical axis).
    The camera looks along the component's +x. Nothing is rendered."""

    short_descr = "Names and poses of the tagged objects in the camera's field of view"
    builder_name = "SemanticCamera"
    frequency = 20.0

    class Properties(CameraProperties):
        # the picture's size and lens give the field of view, read at every tick; nothing is rendered
        cam_width: int = Field(256, ge=1, description="image width, pixels: with cam_height and the lens, the "
                               "field of view (read at every tick)")
        cam_height: int = Field(256, ge=1, description="image height, pixels (read at every tick)")
        cam_focal: float = Field(35.0, gt=0, description="focal length, mm, for a 32 mm sensor across the larger "
                                 "image side (read at every tick)")
        Vertical_Flip: bool = Field(True, description=NO_EFFECT)
        capturing: bool = Field(True, description=NO_EFFECT + " (MORSE's semantic camera ignores it too)")
        retrieve_depth: bool = Field(False, description=NO_EFFECT)
        retrieve_zbuffer: bool = Field(False, description=NO_EFFECT)
        shadows: bool = Field(False, description=NO_EFFECT)
        relative: bool = Field(False, description="poses in the camera's frame (MORSE's camera convention: x "
                               "right, y down, z forward along the optical axis) instead of the world's")
        noocclusion: bool = Field(False, description="do not check that something hides the object: skip the "
                                  "occlusion ray (faster, less realistic)")
        tag: str = Field("Object", description="objects tracked: robots and objects whose property of this name "
                         "is true, or whose Type equals it")

    data = (
        DataField("visible_objects", [], "list[dict]",
                  "one mapping per object seen, in scene order: {name (its Label property or its name), "
                  "description (Description property or ''), type (Type property or ''), position [x, y, z] m, "
                  "orientation {x, y, z, w} quaternion}: the object's origin and orientation in the world frame, "
                  "or in the camera frame (x right, y down, z forward: MORSE's camera convention) when relative"),
        INTRINSIC_MATRIX,
    )

    def start(self) -> None:
        m = self.sim.model
        p = self.properties
        self.local_data["intrinsic_matrix"] = p.intrinsic_matrix
        cam = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_CAMERA, self.name)
        if cam >= 0:  # for `morsec render --camera`: the same view as the frustum below
            m.cam_fovy[cam] = p.fovy
        # the geoms whose boxes make up each object's bounding box: visible ones of its kinematic tree
        tree = m.body_rootid[m.geom_bodyid]
        visible = (m.geom_group < 3) & (m.geom_type != mujoco.mjtGeom.mjGEOM_PLANE)
        self._geoms = {}
        for obj in self.sim.objects:
            geoms = np.flatnonzero((tree == obj.body_id) & visible)
            if len(geoms) == 0:
                geoms = np.flatnonzero((tree == obj.body_id) & (m.geom_type != mujoco.mjtGeom.mjGEOM_PLANE))
            self._geoms[obj.name] = geoms
        root = m.body_rootid[self.body_id]
        self._root = int(root)
        own = np.flatnonzero((tree == root) & (m.geom_group < HIDDEN_GROUP)) if root != 0 else np.array([], int)
        self._own, self._own_groups = own, m.geom_group[own].copy()
        self._hit = np.zeros(1, dtype=np.int32)

    # ---- geometry
    def _frustum_planes(self) -> np.ndarray:
        """Inward normals n and offsets c of the 6 planes (n . p + c >= 0 inside), camera frame x forward."""
        p = self.properties
        f = p.focal_pixels
        th, tv = p.cam_width / 2.0 / f, p.cam_height / 2.0 / f
        return np.array([
            [1.0, 0.0, 0.0, -p.cam_near],
            [-1.0, 0.0, 0.0, p.cam_far],
            [th, -1.0, 0.0, 0.0],  # left edge (+y side)
            [th, 1.0, 0.0, 0.0],  # right edge
            [tv, 0.0, -1.0, 0.0],  # top
            [tv, 0.0, 1.0, 0.0],  # bottom
        ])

    def _corners(self, geoms: np.ndarray) -> np.ndarray:
        """World corners (8 per geom) of the geoms' boxes (MuJoCo's geom_aabb, in each geom's frame)."""
        m, d = self.sim.model, self.sim.data
        aabb = m.geom_aabb[geoms]  # center (3), half sizes (3), geom frame
        local = aabb[:, None, :3] + _SIGNS[None, :, :] * aabb[:, None, 3:]
        rot = d.geom_xmat[geoms].reshape(-1, 3, 3)
        return (np.einsum("gij,gkj->gki", rot, local) + d.geom_xpos[geoms][:, None, :]).reshape(-1, 3)

    def in_frustum(self, corners: np.ndarray, origin: np.ndarray, rot: np.ndarray, planes: np.ndarray) -> bool:
        local = (corners - origin) @ rot  # camera frame
        outside = (local @ planes[:, :3].T + planes[:, 3]) < 0.0  # corners x planes
        return not outside.all(axis=0).any()  # outside only if every corner is outside one same plane

    def unoccluded(self, obj, origin: np.ndarray, target: np.ndarray) -> bool:
        """The first thing a ray from the camera to `target` meets belongs to the object."""
        m, d = self.sim.model, self.sim.data
        hide = len(self._own) > 0
        if hide:
            m.geom_group[self._own] = HIDDEN_GROUP
        try:
            dist = mujoco.mj_ray(m, d, origin, target - origin, SEEN_GROUPS, 1, -1, self._hit)
        finally:
            if hide:
                m.geom_group[self._own] = self._own_groups
        if dist < 0:
            return False
        return int(m.body_rootid[m.geom_bodyid[self._hit[0]]]) == obj.body_id

    # ---- the tick
    def default_action(self) -> None:
        p = self.properties
        d = self.sim.data
        origin, rot = self.position().copy(), self.rotation().copy()
        planes = self._frustum_planes()
        seen = []
        for obj in self.sim.objects_with(p.tag):
            geoms = self._geoms.get(obj.name)
            if obj.body_id == self._root or geoms is None or len(geoms) == 0:
                continue
            corners = self._corners(geoms)
            if not self.in_frustum(corners, origin, rot, planes):
                continue
            centre = (corners.min(axis=0) + corners.max(axis=0)) / 2.0  # of its world bounding box
            if not p.noocclusion and not self.unoccluded(obj, origin, centre):
                continue
            pos = d.xpos[obj.body_id]
            orient = d.xmat[obj.body_id].reshape(3, 3)
            if p.relative:  # in the camera's optical frame, as MORSE's cameras
                optical = rot @ OPTICAL_TO_COMPONENT
                pos, orient = optical.T @ (pos - origin), optical.T @ orient
            w, x, y, z = matrix_to_quat(orient)
            props = obj.properties
            seen.append({
                "name": str(props.get("Label", obj.name)),
                "description": str(props.get("Description", "")),
                "type": str(props.get("Type", "")),
                "position": [float(v) for v in pos],
                "orientation": {"x": float(x), "y": float(y), "z": float(z), "w": float(w)},
            })
        self.local_data["visible_objects"] = seen


COMPONENT = SemanticCamera
