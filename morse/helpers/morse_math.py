"""MORSE's `morse.helpers.morse_math`: angle helpers."""

from morsec.kits.geometry import normalize_angle as normalise_angle

__all__ = ["normalise_angle"]
