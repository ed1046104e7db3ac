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


def bounded_floats(values, limit: float, what: str) -> tuple[float, ...]:
    """bounded's check, the values as a tuple of floats: cheaper than an array for the few numbers of a
    command given every tick (a 3-vector, the usual one, unrolled: a robot's speeds at every frame)."""
    try:
        x, y, z = values
        floats: tuple[float, ...] = (float(x), float(y), float(z))
    except (TypeError, ValueError):  # not 3 numbers
        try:
            floats = tuple(map(float, values))
        except (TypeError, ValueError):
            return tuple(bounded(values, limit, what).tolist())  # bounded's error for what is not numbers
        for value in floats:
            if not abs(value) <= limit:  # NaN fails the comparison too
                bounded(floats, limit, what)
        return floats
    if not (abs(floats[0]) <= limit and abs(floats[1]) <= limit and abs(floats[2]) <= limit):  # NaN fails too
        bounded(floats, limit, what)
    return floats
