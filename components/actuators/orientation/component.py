from __future__ import annotations

import math

import numpy as np
from pydantic import Field

from morsec.component import Actuator, ControlTypeProperties, DataField
from morsec.kits.geometry import euler_to_quat, normalize_angle, quat_to_matrix
from morsec.modifiers.coordinates import AnglesFromNED


def _no_default(schema: dict) -> None:
    schema.pop("default", None)  # inf is not JSON: the description says it


class Orientation(Actuator):
    """Turns the robot so that this actuator's frame has the commanded yaw, pitch and roll (MORSE's
    Orientation): instantly with the default infinite `speed`, else at no more than `speed` rad/s about
    each angle, each stopping within `tolerance` of its goal. As MORSE's, the rate of each angle is set as
    the robot's angular velocity about its own axis of the same name (roll: x, pitch: y, yaw: z)."""

    short_descr = "Set the orientation of the robot"
    builder_name = "Orientation"
    frequency = 60.0
    modifiers = {"ned": AnglesFromNED}
    base_servo = True

    class Properties(ControlTypeProperties):
        speed: float = Field(math.inf, gt=0, allow_inf_nan=True, json_schema_extra=_no_default,
                             description="rotation speed, rad/s; default inf: the rotation is instantaneous "
                             "(write .inf in YAML, inf in TOML)")
        tolerance: float = Field(0.02, ge=0, description="angle, rad, under which a goal angle is reached")

    data = (
        DataField("yaw", 0.0, "float", "rotation about z, rad (default: the initial orientation)"),
        DataField("pitch", 0.0, "float", "rotation about y, rad"),
        DataField("roll", 0.0, "float", "rotation about x, rad"),
    )

    def start(self):
        roll, pitch, yaw = self.euler()
        self.local_data.update(yaw=yaw, pitch=pitch, roll=roll)

    def default_action(self):
        d = self.local_data
        goal = (float(d["roll"]), float(d["pitch"]), float(d["yaw"]))
        if math.isinf(self.properties.speed):
            target = quat_to_matrix(euler_to_quat(*goal))
            current = self.rotation()
            angle = math.acos(max(-1.0, min(1.0, (float(np.trace(current.T @ target)) - 1) / 2)))
            if angle > 1e-9:  # set_pose stops the robot: only when there is something to turn
                self.robot.place_frame(self.body_id, self.position().copy(), target)
            return
        roll, pitch, yaw = self.euler()
        rates = []
        for want, have in zip(goal, (roll, pitch, yaw)):
            diff = normalize_angle(want - have)
            if abs(diff) < self.properties.tolerance:
                rates.append(0.0)
            else:
                rates.append(math.copysign(min(self.properties.speed, abs(diff) * self.frequency), diff))
        # as MORSE's: the roll, pitch and yaw rates are the robot's angular velocity about its own x, y, z
        # axes (exact for a yaw alone; pitched or rolled, the angles take a curved path to their goals,
        # and an Attitude sensor reads these rates)
        self.robot.apply_speed(self.properties.ControlType, [0.0, 0.0, 0.0], rates, self.frequency)


COMPONENT = Orientation
