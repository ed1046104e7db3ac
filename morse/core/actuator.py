"""MORSE's `morse.core.actuator.Actuator`: a MORSE actuator class is a morsec actuator
(`morsec.component.Actuator`), declared and built MORSE's way (morse.core.object). A client's message replaces
`local_data` before each `default_action`, as morsec's actuators read it. An actuator whose code calls
`robot_parent.apply_speed` drives its robot through morsec's base servos, as morsec's MotionVW does."""

from __future__ import annotations

import inspect

from morse.core.object import Object
from morsec.component.contract import Actuator as MorsecActuator

__all__ = ["Actuator"]


def _drives_speed(cls) -> bool:
    """Whether the class (or a MORSE-API class it derives from) calls apply_speed."""
    for klass in cls.__mro__:
        if not getattr(klass, "_morse_api", False) or klass.__module__.startswith(("morse.", "morsec.")):
            continue
        try:
            if "apply_speed" in inspect.getsource(klass):
                return True
        except (OSError, TypeError):
            continue
    return False


class Actuator(Object, MorsecActuator):
    """Base of MORSE's actuators: `default_action` applies `self.local_data`."""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "base_servo" not in vars(cls):
            cls.base_servo = _drives_speed(cls)

    def __init__(self, obj, parent=None):
        Object.__init__(self, obj, parent)
        self.input_functions: list = []
        self.input_modifiers: list = []
