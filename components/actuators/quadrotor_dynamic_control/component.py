import math
from typing import Literal

import numpy as np
from pydantic import Field

from morsec.component import Actuator, ComponentProperties, DataField


class QuadrotorDynamicControl(Actuator):
    """Rotor speeds of a quadrotor turned into a thrust and torques on its body, as MORSE's
    QuadrotorDynamicControl (the dynamic model of Bouabdallah's micro quadrotor): with w_i the speed of
    rotor i, b = ThrustFactor, d = DragFactor, l = Lever,

        thrust (along the robot's z) = b (w1^2 + w2^2 + w3^2 + w4^2)
        '+':  roll = b l (w4^2 - w2^2),  pitch = b l (w1^2 - w3^2)
        'x':  roll = b l sqrt(2)/2 (w1^2 - w2^2 - w3^2 + w4^2),
              pitch = b l sqrt(2)/2 (-w1^2 - w2^2 + w3^2 + w4^2)
        yaw = d (-w1^2 + w2^2 - w3^2 + w4^2)

    (rotors 1 and 3 turn clockwise, 2 and 4 counter-clockwise), in the robot's frame, applied at its
    centre of mass through MuJoCo's `xfrc_applied`, re-applied until the next command."""

    short_descr = "Quadrotor thrust and torques from its four rotor speeds"
    builder_name = "QuadrotorDynamicControl"
    frequency = 60.0

    class Properties(ComponentProperties):
        ThrustFactor: float = Field(9.169e-06, description="thrust factor, N s^2")
        DragFactor: float = Field(2.4e-7, description="drag factor, N m s^2")
        Lever: float = Field(0.18, description="distance between the centre of mass and a propeller, m")
        Configuration: Literal["+", "x"] = Field(
            "+", description="'+': the drone's x axis follows the front arm; 'x': it lies between the two "
            "front arms")

    data = (
        DataField("engines", [0.0, 0.0, 0.0, 0.0], "vec4", "speed of each engine, rad/s"),
    )

    def transformation(self) -> np.ndarray:
        """The 4x4 matrix from squared rotor speeds to (thrust, roll, pitch, yaw torques)."""
        b, d, lever = self.properties.ThrustFactor, self.properties.DragFactor, self.properties.Lever
        bl = b * lever
        if self.properties.Configuration == "+":
            return np.array([[b, b, b, b],
                             [0.0, -bl, 0.0, bl],
                             [bl, 0.0, -bl, 0.0],
                             [-d, d, -d, d]])
        bl_sq = bl * math.sqrt(2) / 2
        return np.array([[b, b, b, b],
                         [bl_sq, -bl_sq, -bl_sq, bl_sq],
                         [-bl_sq, -bl_sq, bl_sq, bl_sq],
                         [-d, d, -d, d]])

    def default_action(self):
        engines = np.asarray(self.local_data["engines"], float).reshape(4)
        thrust, *torque = self.transformation() @ (engines * engines)
        rot = self.sim.data.xmat[self.robot.body_id].reshape(3, 3)
        self.robot.apply_wrench(self.name, rot @ np.array([0.0, 0.0, thrust]), rot @ np.asarray(torque))


COMPONENT = QuadrotorDynamicControl
