from __future__ import annotations

import numpy as np
from pydantic import Field

from morsec.component import Actuator, ControlTypeProperties, DataField
from morsec.modifiers.coordinates import POSITION_IN


class Destination(Actuator):
    """Moves the robot in a straight line towards a goal, without turning (MORSE's Destination): every tick
    the robot's velocity is the unit vector from this actuator to the goal times Speed, until the actuator
    is within Tolerance of the goal; status "Transit", then "Stop". A ground robot is driven in the plane
    (the distance and the direction are planar: it cannot change its height itself)."""

    short_descr = "Move the robot in a straight line to a goal point"
    builder_name = "Destination"
    frequency = 60.0
    modifiers = POSITION_IN
    base_servo = True

    class Properties(ControlTypeProperties):
        Tolerance: float = Field(0.5, ge=0, description="distance to the goal, m, under which it is reached")
        Speed: float = Field(5.0, description="speed of the movement, m/s")
        RemainAtDestination: bool = Field(False, description="keep servoing to the goal once reached (flying "
                                          "robots that would otherwise drift or fall)")

    data = (
        DataField("x", 0.0, "float", "x of the goal, world frame, m (default: the actuator's initial position)"),
        DataField("y", 0.0, "float", "y of the goal, world frame, m"),
        DataField("z", 0.0, "float", "z of the goal, world frame, m (ignored by ground robots)"),
    )

    def start(self):
        x, y, z = (float(v) for v in self.position())
        self.local_data.update(x=x, y=y, z=z)
        self.status = "Stop"
        self._previous = self._goal()

    def _goal(self) -> tuple[float, float, float]:
        d = self.local_data
        return float(d["x"]), float(d["y"]), float(d["z"])

    def default_action(self):
        goal = self._goal()
        previous, self._previous = self._previous, goal
        if not self.properties.RemainAtDestination and self.status == "Stop" and goal == previous:
            return  # reached and no new goal: leave the robot alone
        delta = np.array(goal) - self.position()
        if self.robot.ground:
            delta[2] = 0.0
        distance = float(np.linalg.norm(delta))
        control = self.properties.ControlType
        if distance <= self.properties.Tolerance:
            self.status = "Stop"
            self.robot.apply_speed(control, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], self.frequency)
            return
        self.status = "Transit"
        speed = min(float(self.properties.Speed), distance * self.frequency)  # no overshoot in one tick
        world = delta / distance * speed
        _, rot = self.robot.pose()
        self.robot.apply_speed(control, rot.T @ world, [0.0, 0.0, 0.0], self.frequency)


COMPONENT = Destination
