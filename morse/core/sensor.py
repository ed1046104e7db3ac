"""MORSE's `morse.core.sensor.Sensor`: a MORSE sensor class is a morsec sensor (`morsec.component.Sensor`),
declared and built MORSE's way (morse.core.object). Its `timestamp` is morsec's (simulated s), set before each
`default_action`; its streams publish `local_data` on every middleware."""

from __future__ import annotations

from morse.core.object import Object
from morsec.component.contract import Sensor as MorsecSensor

__all__ = ["Sensor"]


class Sensor(Object, MorsecSensor):
    """Base of MORSE's sensors: `default_action` fills `self.local_data`."""

    def __init__(self, obj, parent=None):
        Object.__init__(self, obj, parent)
        self.output_functions: list = []
        self.output_modifiers: list = []
        self.profile = None

    def sensor_to_robot_position_3d(self):
        """The transformation from the robot's frame to the sensor's."""
        return self.robot_parent.position_3d.transformation3d_with(self.position_3d)
