"""MORSE's `morse.helpers.morse_math`: angle helpers."""

import math

__all__ = ["normalise_angle"]


def normalise_angle(angle):
    """The angle in [-pi, pi)."""
    return ((angle + math.pi) % (2 * math.pi)) - math.pi

