"""MORSE's Gripper: grab the nearest `Graspable` object in a cone in front of the gripper, carry it, let it go.

MORSE parents the object to the gripper. Here a dynamic object is held by a MuJoCo weld constraint
between the gripper's body and the object, declared for every dynamic Graspable object of the scene
(equality.xml.j2) and switched on by `grab` (`data.eq_active`) with the relative pose of that moment
(`model.eq_data`): the object follows the gripper through the physics, with its mass, and falls when
released. A static Graspable object (no free joint) is carried kinematically: put at the same relative
pose every tick, and left where it is when released.
"""

from __future__ import annotations

import logging
import math

import mujoco
import numpy as np
from pydantic import Field

from morsec.component import Actuator, ComponentProperties, DataField, service
from morsec.kits.geometry import matrix_to_quat

log = logging.getLogger("morsec.actuators.gripper")
JUMP = 0.05  # m: a held object this far from where the hand holds it is put back there


class Gripper(Actuator):
    """Grabs the nearest object having the `Graspable` property whose bounding box comes within `Distance`
    of the gripper's origin inside a cone of full aperture `Angle` (degrees) around its +x axis, and carries it until
    `release`. The fingers are visual only: nothing about the grasp is simulated but the holding."""

    short_descr = "Grab the nearest Graspable object in front of the gripper, and release it"
    builder_name = "Gripper"
    frequency = 60.0

    class Properties(ComponentProperties):
        Angle: float = Field(60.0, gt=0, le=360.0,
                             description="full aperture of the detection cone around the gripper's +x axis, "
                             "degrees (MORSE's radar angle)")
        Distance: float = Field(0.5, gt=0, description="objects farther than this from the gripper's origin "
                                "(nearest point of their bounding box) cannot be grabbed, m")

    data = (
        DataField("grab", False, "bool", "true: hold (grab the nearest Graspable object in the cone, as the "
                  "`grab` service), false: release; the services set it, it is true while an object is held"),
    )

    def start(self):
        m = self.sim.model
        self.graspable = []  # (object name, body, weld id or -1 for a static object)
        for obj in self.sim.objects:
            if obj.kind != "object" or not obj.properties.get("Graspable") or obj.body_id < 0:
                continue
            weld = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_EQUALITY, f"{self.name}/{obj.name}")
            self.graspable.append((obj.name, obj.body_id, weld))
        self.held: tuple | None = None  # (name, body, weld, relative position, relative rotation)

    # ------------------------------------------------------------------ detection
    def in_reach(self) -> list[tuple[float, str]]:
        """(distance, name) of the Graspable objects in the cone, nearest first."""
        m, d = self.sim.model, self.sim.data
        origin, axis = self.position().copy(), self.rotation()[:, 0].copy()
        half = math.radians(self.properties.Angle) / 2
        found = []
        for name, body, _ in self.graspable:
            best, best_point = math.inf, d.xpos[body].copy()
            for g in np.flatnonzero(m.geom_bodyid == body):
                rot, center, halfsize = d.geom_xmat[g].reshape(3, 3), m.geom_aabb[g, :3], m.geom_aabb[g, 3:]
                local = rot.T @ (origin - d.geom_xpos[g]) - center
                nearest = np.clip(local, -halfsize, halfsize)
                dist = float(np.linalg.norm(local - nearest))
                if dist < best:
                    best, best_point = dist, d.geom_xpos[g] + rot @ (nearest + center)
            if best > self.properties.Distance:
                continue
            if best == 0.0 or any(_in_cone(p - origin, axis, half) for p in (d.xpos[body], best_point)):
                found.append((best, name))
        return sorted(found)

    # ------------------------------------------------------------------ holding
    def _grab(self) -> str | None:
        reach = self.in_reach()
        if not reach:
            return None
        name = reach[0][1]
        _, body, weld = next(g for g in self.graspable if g[0] == name)
        d = self.sim.data
        rot = self.rotation()
        rel_pos = rot.T @ (d.xpos[body] - self.position())
        rel_rot = rot.T @ d.xmat[body].reshape(3, 3)
        if weld >= 0:
            eq = self.sim.model.eq_data[weld]
            eq[0:3] = 0.0
            eq[3:6] = rel_pos
            eq[6:10] = matrix_to_quat(rel_rot)
            d.eq_active[weld] = 1
        self.held = (name, body, weld, rel_pos, rel_rot)
        log.debug("%s: grabbed %s", self.name, name)
        return name

    def _release(self) -> bool:
        if self.held is None:
            return False
        _, _, weld, _, _ = self.held
        if weld >= 0:
            self.sim.data.eq_active[weld] = 0
        self.held = None
        return True

    def default_action(self):
        want = bool(self.local_data.get("grab", False))
        if want and self.held is None:
            self._grab()
        elif not want and self.held is not None:
            self._release()
        if self.held is not None:
            _, body, weld, rel_pos, rel_rot = self.held
            rot = self.rotation()
            pos = self.position() + rot @ rel_pos
            # a static object is carried kinematically; a welded one is put back in the hand when the gripper
            # jumped (its robot teleported: MORSE's object, parented to the gripper, went along), where the
            # weld alone would pull it across the gap at once
            if weld < 0 or float(np.linalg.norm(self.sim.data.xpos[body] - pos)) > JUMP:
                self.sim.place_body(body, pos, rot @ rel_rot)

    # ------------------------------------------------------------------ services
    @service
    def grab(self) -> str | None:
        """Grab the nearest Graspable object in the cone. Returns its name (the one already held, if any), or
        None when there is none within reach."""
        if self.held is None:
            self._grab()
        self.local_data["grab"] = self.held is not None
        return self.held[0] if self.held else None

    @service
    def release(self) -> bool:
        """Let the held object go (a dynamic one falls). Returns True if one was held, else False."""
        self.local_data["grab"] = False
        return self._release()


def _in_cone(v: np.ndarray, axis: np.ndarray, half_angle: float) -> bool:
    n = float(np.linalg.norm(v))
    return n == 0.0 or math.acos(max(-1.0, min(1.0, float(axis @ v) / n))) <= half_angle


COMPONENT = Gripper
