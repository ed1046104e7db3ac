"""MORSE's PTU (pan-tilt unit): two real hinge joints, pan about the unit's z axis then tilt about the pan
body's y axis, held by MuJoCo position servos whose setpoints move towards the `pan` / `tilt` fields at
`Speed` rad/s (each axis on its own, as MORSE's `rotation_direction`). A movement is over when both joints
are within `Tolerance` of their targets: a pending `set_pan_tilt`, `look_at_point` or `look_at_object`
then answers SUCCESS. Components appended to the unit (a camera) ride on the tilt body (`mount_body`).
"""

from __future__ import annotations

import math

import numpy as np
from pydantic import Field

from morsec.component import Actuator, ComponentProperties, DataField, async_service, service
from morsec.kits.geometry import normalize_angle
from morsec.kits.servos import JointServos


class PTU(Actuator):
    """A pan-tilt unit: pan about its z axis (positive turns left), then tilt about the pan body's y axis
    (positive looks down), at `Speed` rad/s within `Tolerance`. A camera appended to it is mounted on the
    tilt body and turns with it. Targets are normalised to [-pi, pi]."""

    short_descr = "Pan-tilt unit: pan and tilt joints driven at a given speed"
    builder_name = "PTU"
    frequency = 60.0
    mount_body = "tilt"  # children components are nested in body <fqn>/tilt (read by the compiler)

    class Properties(ComponentProperties):
        Speed: float = Field(1.0, gt=0, description="rotation speed of each axis, rad/s")
        Tolerance: float = Field(math.radians(0.3), gt=0,
                                 description="angle, rad, within which a target counts as reached")
        Manual: bool = Field(False, description="True: the fields and services do not move the unit; its "
                             "servos follow the joints wherever they are pushed (by hand in the viewer)")

    data = (
        DataField("pan", 0.0, "float", "pan target, rad, about the unit's z axis (positive: to the left)"),
        DataField("tilt", 0.0, "float", "tilt target, rad, about the pan body's y axis (positive: down)"),
    )

    def start(self):
        self.servos = JointServos(self.sim, self.name)
        missing = {"pan", "tilt"} - set(self.servos.names)
        if missing:
            raise ValueError(f"its model has no joint {', '.join(sorted(missing))}: rebuild the scene")
        self._pan, self._tilt = self.servos.index["pan"], self.servos.index["tilt"]
        self.servos.command(self.servos.positions())

    def reset(self):
        self.local_data["pan"], self.local_data["tilt"] = self.current()  # the restored initial angles
        self.servos.command(self.servos.positions())

    # ------------------------------------------------------------------ state
    def current(self) -> tuple[float, float]:
        q = self.servos.positions()
        return float(q[self._pan]), float(q[self._tilt])

    def targets(self) -> np.ndarray:
        out = np.zeros(len(self.servos.names))
        out[self._pan] = normalize_angle(float(self.local_data["pan"]))
        out[self._tilt] = normalize_angle(float(self.local_data["tilt"]))
        return out

    # ------------------------------------------------------------------ the tick
    def default_action(self):
        servos = self.servos
        q = servos.positions()
        if self.properties.Manual:
            servos.command(q)  # no stiffness against a push: the setpoint follows the joint
            return
        target = self.targets()
        step = self.properties.Speed / self.frequency
        delta = np.clip(target - servos.setpoint, -step, step)
        velocity = delta * self.frequency
        servos.command(servos.setpoint + delta, velocity)
        if np.all(np.abs(target - q) < self.properties.Tolerance):
            self.completed("SUCCESS")

    # ------------------------------------------------------------------ services
    @async_service(interruptible=True)
    def set_pan_tilt(self, pan: float, tilt: float) -> None:
        """Turn to (pan, tilt), rad; answers SUCCESS when both are within Tolerance."""
        self.local_data["pan"], self.local_data["tilt"] = float(pan), float(tilt)

    @service
    def get_pan_tilt(self) -> list[float]:
        """The current [pan, tilt] of the joints, rad."""
        return list(self.current())

    @async_service(interruptible=True)
    def look_at_point(self, x: float, y: float, z: float) -> None:
        """Aim the tilt body's x axis (a camera mounted on it) at the world point (x, y, z), m."""
        self.local_data["pan"], self.local_data["tilt"] = self.aim(np.array([x, y, z], dtype=float))

    @async_service(interruptible=True)
    def look_at_object(self, obj_name: str) -> None:
        """Aim at the origin of a scene object (or robot) named `obj_name`."""
        import mujoco
        found = next((o for o in self.sim.objects if o.name == obj_name), None)
        body = found.body_id if found is not None else \
            mujoco.mj_name2id(self.sim.model, mujoco.mjtObj.mjOBJ_BODY, str(obj_name))
        if body is None or body < 0:
            from morsec.errors import did_you_mean
            raise ValueError(f"no object {obj_name!r} in the scene"
                             f"{did_you_mean(str(obj_name), [o.name for o in self.sim.objects])}")
        self.local_data["pan"], self.local_data["tilt"] = self.aim(self.sim.data.xpos[body].copy())

    def aim(self, point: np.ndarray) -> tuple[float, float]:
        """(pan, tilt) that turn the tilt body's x axis parallel to the direction from the unit's origin to a
        world point, as MORSE's (which aimed from the unit's origin, not from the tilt axis above it): that
        direction in the unit's own (unpanned) frame gives both angles."""
        v = self.rotation().T @ (point - self.position())
        if not np.any(v):
            raise ValueError("the point is at the centre of the unit: no direction to look at")
        return float(math.atan2(v[1], v[0])), float(math.atan2(-v[2], math.hypot(v[0], v[1])))

    def interrupt(self) -> None:
        """A cancelled (or preempted) movement stops where the unit is."""
        self.local_data["pan"], self.local_data["tilt"] = self.current()
        self.servos.setpoint = self.servos.positions()


COMPONENT = PTU
