"""Modifiers (`alter`): post-processors on a sensor's output or an actuator's input (reference §4.1)."""

from morsec.modifiers.registry import MODIFIERS, modifier_class

__all__ = ["MODIFIERS", "modifier_class"]
