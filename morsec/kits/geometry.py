"""Frames and rotations, with MORSE's conventions: XYZ Euler angles (roll about x, then pitch about y,
then yaw about z, in fixed axes, as Blender), quaternions as (w, x, y, z) as MuJoCo."""

from __future__ import annotations

import math

import numpy as np


def euler_to_quat(rx: float, ry: float, rz: float) -> np.ndarray:
    """Quaternion (w, x, y, z) of R = Rz(rz) @ Ry(ry) @ Rx(rx)."""
    return np.array(euler_to_quat_tuple(rx, ry, rz))


def euler_to_quat_tuple(rx: float, ry: float, rz: float) -> tuple[float, float, float, float]:
    """euler_to_quat as a tuple of floats, for a caller that packs it (no array to make)."""
    cx, sx = math.cos(rx / 2), math.sin(rx / 2)
    cy, sy = math.cos(ry / 2), math.sin(ry / 2)
    cz, sz = math.cos(rz / 2), math.sin(rz / 2)
    return (cz * cy * cx + sz * sy * sx, cz * cy * sx - sz * sy * cx, cz * sy * cx + sz * cy * sx,
            sz * cy * cx - cz * sy * sx)


def matrix_to_euler(r: np.ndarray) -> tuple[float, float, float]:
    """(roll, pitch, yaw) of a rotation matrix R = Rz(yaw) @ Ry(pitch) @ Rx(roll), chosen as Blender chose
    (see euler_of_xmat)."""
    return euler_of_xmat(np.asarray(r, float).reshape(9).tolist())


def quat_to_matrix(q) -> np.ndarray:
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def matrix_to_quat(r: np.ndarray) -> np.ndarray:
    r = np.asarray(r).reshape(3, 3)
    trace = r[0, 0] + r[1, 1] + r[2, 2]
    if trace > 0:
        s = math.sqrt(trace + 1.0) * 2
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    elif r[0, 0] > r[1, 1] and r[0, 0] > r[2, 2]:
        s = math.sqrt(1.0 + r[0, 0] - r[1, 1] - r[2, 2]) * 2
        q = [(r[2, 1] - r[1, 2]) / s, 0.25 * s, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s]
    elif r[1, 1] > r[2, 2]:
        s = math.sqrt(1.0 + r[1, 1] - r[0, 0] - r[2, 2]) * 2
        q = [(r[0, 2] - r[2, 0]) / s, (r[0, 1] + r[1, 0]) / s, 0.25 * s, (r[1, 2] + r[2, 1]) / s]
    else:
        s = math.sqrt(1.0 + r[2, 2] - r[0, 0] - r[1, 1]) * 2
        q = [(r[1, 0] - r[0, 1]) / s, (r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, 0.25 * s]
    q = np.array(q)
    return q if q[0] >= 0 else -q


def normalize_angle(a: float) -> float:
    return (a + math.pi) % (2 * math.pi) - math.pi


def fmt(x: float) -> str:
    """Deterministic, compact number formatting for generated files."""
    s = f"{float(x):.10g}"
    return "0" if s in ("-0", "0") else s


def fmt_vec(values) -> str:
    return " ".join(fmt(v) for v in values)


# ---- the same on plain floats: a rotation matrix as MuJoCo's xmat row-major 9-list. A few microseconds
# less per call than numpy on 3x3, which matters for sensors ticking every frame.

# Below this, cos(pitch) is taken for 0 (pitch +-90 degrees): Blender's threshold, 16 float epsilons
GIMBAL_LOCK = 16 * 1.1920929e-07
_HALF_THREE_PI = 1.5 * math.pi - 1e-9  # below it, rounding cannot make the two sums compare otherwise
_atan2, _hypot = math.atan2, math.hypot  # module globals: a little cheaper than math's attributes, per frame


def euler_of_xmat(m) -> tuple[float, float, float]:
    """(roll, pitch, yaw) of a row-major 3x3 rotation R = Rz(yaw) @ Ry(pitch) @ Rx(roll), as Blender's
    matrix-to-Euler gave MORSE: of the two triples that make the same rotation (pitch in [-pi/2, pi/2], or
    pitch beyond it with roll and yaw turned by pi), the one with the smaller sum of absolute angles (the
    first on a tie). A rotation of pi about y reads (0, pi, 0), not (pi, 0, pi). In gimbal lock (pitch
    +-90 degrees) the rest of the rotation goes in roll and yaw is 0."""
    r00, r10, r20 = m[0], m[3], m[6]
    cy = _hypot(r00, r10)
    if cy <= GIMBAL_LOCK:
        return _atan2(-m[5], m[4]), _atan2(-r20, cy), 0.0
    return _euler_unlocked(r00, r10, r20, m[7], m[8], cy)


def euler_of_transpose_times(a, b) -> tuple[float, float, float]:
    """euler_of_xmat(transpose_times(a, b)), the same to the bit: only the entries of Aᵀ B it reads are
    computed (5 of 9, 7 in gimbal lock). Odometry takes two such relative rotations at every tick."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8 = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8 = b
    r00 = a0 * b0 + a3 * b3 + a6 * b6
    r10 = a1 * b0 + a4 * b3 + a7 * b6
    r20 = a2 * b0 + a5 * b3 + a8 * b6
    cy = _hypot(r00, r10)
    if cy <= GIMBAL_LOCK:
        r11, r12 = a1 * b1 + a4 * b4 + a7 * b7, a1 * b2 + a4 * b5 + a7 * b8
        return _atan2(-r12, r11), _atan2(-r20, cy), 0.0
    return _euler_unlocked(r00, r10, r20, a2 * b1 + a5 * b4 + a8 * b7, a2 * b2 + a5 * b5 + a8 * b8, cy)


def _euler_unlocked(r00: float, r10: float, r20: float, r21: float, r22: float,
                    cy: float) -> tuple[float, float, float]:
    """euler_of_xmat out of gimbal lock, from the entries it reads and cy = hypot(r00, r10)."""
    roll, pitch, yaw = _atan2(r21, r22), _atan2(-r20, cy), _atan2(r10, r00)
    # each angle of the second triple is pi less the first's in absolute value: its sum is 3 pi less the
    # first's, the larger one when the first's is clearly below 3 pi / 2 (no need to compute it then)
    first = abs(roll) + abs(pitch) + abs(yaw)
    if first < _HALF_THREE_PI:
        return roll, pitch, yaw
    second = (_atan2(-r21, -r22), _atan2(-r20, -cy), _atan2(-r10, -r00))
    if first > abs(second[0]) + abs(second[1]) + abs(second[2]):
        return second
    return roll, pitch, yaw


def transpose_times(a, b) -> list[float]:
    """Aᵀ B for row-major 3x3 matrices given as 9-lists."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8 = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8 = b
    return [a0 * b0 + a3 * b3 + a6 * b6, a0 * b1 + a3 * b4 + a6 * b7, a0 * b2 + a3 * b5 + a6 * b8,
            a1 * b0 + a4 * b3 + a7 * b6, a1 * b1 + a4 * b4 + a7 * b7, a1 * b2 + a4 * b5 + a7 * b8,
            a2 * b0 + a5 * b3 + a8 * b6, a2 * b1 + a5 * b4 + a8 * b7, a2 * b2 + a5 * b5 + a8 * b8]


def times_transpose(a, b) -> list[float]:
    """A Bᵀ for row-major 3x3 matrices given as 9-lists."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8 = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8 = b
    return [a0 * b0 + a1 * b1 + a2 * b2, a0 * b3 + a1 * b4 + a2 * b5, a0 * b6 + a1 * b7 + a2 * b8,
            a3 * b0 + a4 * b1 + a5 * b2, a3 * b3 + a4 * b4 + a5 * b5, a3 * b6 + a4 * b7 + a5 * b8,
            a6 * b0 + a7 * b1 + a8 * b2, a6 * b3 + a7 * b4 + a8 * b5, a6 * b6 + a7 * b7 + a8 * b8]


def transpose_apply(a, v) -> tuple[float, float, float]:
    """Aᵀ v for a row-major 3x3 A and a 3-vector v."""
    x, y, z = v
    return (a[0] * x + a[3] * y + a[6] * z, a[1] * x + a[4] * y + a[7] * z, a[2] * x + a[5] * y + a[8] * z)
