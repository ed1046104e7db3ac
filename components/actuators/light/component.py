"""MORSE's Light: a spot lamp emitting along the component's +x axis, switched on and off.

The lamp is a MuJoCo spot <light> in the component's body (model.xml.j2); switching it changes
`model.light_active`, which the renderer reads: cameras see the change in their next picture.
"""

from __future__ import annotations

import math
import re

import mujoco
from pydantic import Field, field_validator

from morsec.component import Actuator, ComponentProperties, DataField, service

_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def parse_color(text: str) -> tuple[float, float, float]:
    values = [float(v) for v in _NUMBER.findall(text)]
    if len(values) != 3:
        raise ValueError(f"color must be three numbers in 0..1, as \"(1,0.5,0)\", got {text!r}")
    return tuple(min(1.0, max(0.0, v)) for v in values)


class Light(Actuator):
    """A spot light along +x, on while `emit` is true. `toggle()` switches it, `toggle(true/false)` sets it.
    `size` is the cone's full angle, `distance` where the light is half as strong, `energy` scales the
    colour; the default colour "(0,0,0)" means the lamp's own white (MORSE's builder only sets the colour
    you give)."""

    short_descr = "Spot light that can be switched on and off"
    builder_name = "Light"
    frequency = 60.0

    class Properties(ComponentProperties):
        emit: bool = Field(True, description="set to false to start with the light off")
        distance: float = Field(10.0, gt=0, description="distance at which the light energy is halved, m "
                                "(attenuation 1 + (r / distance)^2)")
        color: str = Field("(0,0,0)", description="light colour \"(r,g,b)\" in 0..1; \"(0,0,0)\": the lamp's own "
                           "white (MORSE's builder only sets a colour you give)")
        size: float = Field(math.pi / 2, gt=0, lt=2 * math.pi, description="full angle of the spot's cone, rad "
                            "(MuJoCo cutoff = size / 2)")
        energy: float = Field(1.0, ge=0, description="light energy when on: scales the colour (MuJoCo diffuse = "
                              "colour x energy)")

        @field_validator("color")
        @classmethod
        def _color(cls, value: str) -> str:
            parse_color(value)
            return value

        @property
        def rgb(self) -> list[float]:
            """The light's diffuse colour: colour (white for "(0,0,0)") x energy."""
            color = parse_color(self.color)
            if not any(color):
                color = (1.0, 1.0, 1.0)
            return [c * self.energy for c in color]

    data = (DataField("emit", True, "bool", "on/off switch (streamed in, or the toggle service)"),)

    def start(self):
        self.light = mujoco.mj_name2id(self.sim.model, mujoco.mjtObj.mjOBJ_LIGHT, self.name)
        if self.light < 0:
            raise ValueError("scene.xml has no light for it: rebuild the scene")
        self.local_data["emit"] = bool(self.properties.emit)
        self.sim.model.light_active[self.light] = self.local_data["emit"]

    def default_action(self):
        self.sim.model.light_active[self.light] = bool(self.local_data["emit"])

    @property
    def on(self) -> bool:
        return bool(self.sim.model.light_active[self.light])

    @service
    def toggle(self, emit: bool | None = None) -> bool:
        """Switch the light: on/off when `emit` is true/false, the other way round when it is not given.
        Takes effect at once. Returns True."""
        self.local_data["emit"] = (not bool(self.local_data["emit"])) if emit is None else bool(emit)
        self.sim.model.light_active[self.light] = self.local_data["emit"]
        return True


COMPONENT = Light
