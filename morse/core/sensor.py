"""MORSE's `morse.core.sensor.Sensor`: a MORSE sensor class is a morsec sensor (`morsec.component.Sensor`),
declared and built MORSE's way (morse.core.object). Its `timestamp` is morsec's (simulated s), set before each
`default_action`; its streams publish `local_data` on every middleware."""

from __future__ import annotations

from morse.core.mathutils import _blender  # Blender's package (importing it says how to install it if absent)
from morse.core.object import Object
from morsec.component.contract import Sensor as MorsecSensor

_BLENDER_TYPES = (_blender.Vector, _blender.Matrix, _blender.Quaternion, _blender.Euler, _blender.Color)


def _plain(value):
    """Blender's values as the middlewares carry values: a vector, quaternion or Euler a list, a matrix a list
    of rows (MORSE's serialisers turned them into lists too)."""
    if isinstance(value, _blender.Matrix):
        return [list(row) for row in value]
    if isinstance(value, _BLENDER_TYPES):
        return list(value)
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value

__all__ = ["Sensor"]


class Sensor(Object, MorsecSensor):
    """Base of MORSE's sensors: `default_action` fills `self.local_data`."""

    def __init__(self, obj, parent=None):
        Object.__init__(self, obj, parent)
        self.output_functions: list = []
        self.output_modifiers: list = []
        self.profile = None

    def serialize(self):
        """`local_data`, with Blender's vectors and matrices as lists."""
        data = self.local_data
        if any(isinstance(v, (*_BLENDER_TYPES, dict, list, tuple)) for v in data.values()):
            return {key: _plain(value) for key, value in data.items()}
        return data

    def sensor_to_robot_position_3d(self):
        """The transformation from the robot's frame to the sensor's."""
        return self.robot_parent.position_3d.transformation3d_with(self.position_3d)
