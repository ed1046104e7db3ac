"""MORSE's Keyboard: drive the robot from the keys held in the viewer (`morsec run --view web|native`)."""

from __future__ import annotations

import logging
from typing import Literal

from pydantic import Field

from morsec.component import Actuator, ComponentProperties

log = logging.getLogger("morsec.actuators.keyboard")

# MORSE's keys: {key: (index in (vx, vy, vz, rx, ry, rz), sign)}
KEYMAP = {
    "up": (0, 1.0), "down": (0, -1.0), "left": (1, 1.0), "right": (1, -1.0), "t": (2, 1.0), "g": (2, -1.0),
    "j": (3, -1.0), "l": (3, 1.0), "i": (4, 1.0), "k": (4, -1.0), "u": (5, 1.0), "o": (5, -1.0),
}


class Keyboard(Actuator):
    """Moves its robot from the keys held in the viewer, as MORSE's Keyboard actuator did from Blender's
    window: Up / Down forward and back, Left / Right sideways, T / G up and down, U / O turn left and right
    (at half the speed, rad/s), J / L roll, I / K pitch, each at `Speed`. Opened with `--view web` (keys
    pressed in the browser page) or `--view native`; headless (no viewer), it warns once and does nothing."""

    short_descr = "Drive the robot from the viewer's keyboard (arrows, T/G, U/O, J/L, I/K)"
    builder_name = "Keyboard"
    frequency = 60.0
    base_servo = True

    class Properties(ComponentProperties):
        ControlType: Literal["Position", "Velocity", "Differential"] = Field(
            "Position", description="Position: the robot is displaced by speed / frequency each tick "
            "(kinematically); Velocity: its body velocity is set; Differential: as Velocity, forward speed and "
            "turn rate only (MORSE's wheel drive)")
        Speed: float = Field(1.0, description="movement speed, m/s (the turn rate is Speed / 2, rad/s)")

    data = ()

    def start(self) -> None:
        self._warned = False

    def default_action(self) -> None:
        keys = self.sim.keys
        if keys.source is None:
            if not self._warned:
                self._warned = True
                log.warning("%s: no viewer to read keys from (run with --view web or --view native): the "
                            "keyboard does nothing", self.name)
            return
        motion = [0.0] * 6
        for key in keys.held():
            index, sign = KEYMAP[key]
            motion[index] = sign * self.properties.Speed
        linear, angular = motion[:3], [motion[3], motion[4], motion[5] / 2.0]
        control = self.properties.ControlType
        if control == "Differential":
            linear, angular, control = [linear[0], 0.0, 0.0], [0.0, 0.0, angular[2]], "Velocity"
        self.robot.apply_speed(control, linear, angular, self.frequency)


COMPONENT = Keyboard
