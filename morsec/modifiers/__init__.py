"""Modifiers (`alter`): post-processors on a sensor's output or an actuator's input (reference §4.1).
A component declares which ones apply to it (`Device.modifiers`); `registry.MODIFIERS` holds their names."""

from morsec.modifiers.base import Modifier
from morsec.modifiers.registry import MODIFIERS

__all__ = ["MODIFIERS", "Modifier"]

