"""Where the shipped data folders live, installed (inside the package) or in a source checkout."""

from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent


def data_dir(name: str) -> Path:
    """`components`, `templates` or `schemas`: inside the wheel, else beside the package in the source tree."""
    for candidate in (_PACKAGE / name, _PACKAGE.parent / name):
        if candidate.is_dir():
            return candidate
    raise FileNotFoundError(f"morsec data folder {name!r} not found beside {_PACKAGE}")
