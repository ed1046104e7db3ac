"""Values from a request or a command, checked before they reach MuJoCo's state."""

from __future__ import annotations

import numpy as np


def bounded(values, limit: float, what: str) -> np.ndarray:
    """`values` as an array of floats, or ValueError when one is not finite or beyond ±limit: what a
    request asks for is checked before it reaches MuJoCo's state (an absurd value there makes MuJoCo
    warn "Nan, Inf or huge value" and give up on the step)."""
    array = np.asarray(values, dtype=float)
    if not np.all(np.abs(array) <= limit):  # NaN fails the comparison too
        shown = np.array2string(array, threshold=6, precision=6)
        raise ValueError(f"{what} must be finite and within ±{limit:g}, got {shown}")
    return array


def bounded_floats(values, limit: float, what: str) -> tuple[float, float, float]:
    """bounded's check of a 3-vector (a robot's speeds, at every frame), as a tuple of floats: cheaper than an
    array. ValueError for what is not 3 numbers."""
    try:
        x, y, z = values
        floats = (float(x), float(y), float(z))
    except (TypeError, ValueError):  # not 3 numbers: bounded's error for what is not numbers, else the count's
        raise ValueError(f"{what} must be 3 numbers, got {bounded(values, limit, what).size}") from None
    if not (abs(floats[0]) <= limit and abs(floats[1]) <= limit and abs(floats[2]) <= limit):  # NaN fails too
        bounded(floats, limit, what)
    return floats
