"""morsec: MORSE scenes compiled to MuJoCo."""

__version__ = "0.1.0"

__all__ = ["__version__"]
