"""Following a command held unchanged: what to drive a robot with so that it goes at the command, the command
plus a trim, corrected at each call by what the robot missed over the last interval (RobotHandle.follow).

This runs at every tick of every robot driven by velocity, and it is a hundred float operations: interpreted,
they were a tenth of a small scene's whole loop. So this module is plain typed Python that the package's build
compiles with mypyc (pyproject.toml, the wheel's `mypyc` hook; docs/architecture.md#compiled-module). The same
file runs interpreted where it is not compiled, with the same results to the bit (tests/test_trim.py compares
both). It imports nothing but `math`, and takes and gives plain floats and lists."""

from __future__ import annotations

import math
from typing import Final

GAIN: Final = 0.5  # the part of the last interval's error added to the trim at each call
LIMIT: Final = 0.05  # |trim| <= LIMIT + fraction |command| (a robot held by a wall stays gentle)


class Follow:
    """A command followed by one driver: the last one (vx, vy, wz: body frame; wz about the vertical for a ground
    robot), its trim, how many calls it is held, and the robot's pose at the last call.

    A velocity servo lags its target by (resisting force) / kv: the sideways friction of skidding wheels in a
    turn, a slope; a wheel-driven robot slips. MORSE sets the velocity itself, so a command held unchanged is made
    exact by the trim, corrected at each call by the robot's mean velocity over the last interval (from its poses
    then and now). The trim along an axis is dropped when the command changes direction there."""

    def __init__(self) -> None:
        self.command: tuple[float, float, float] | None = None
        self.trim: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self.held = 0
        self.time = 0.0  # simulated s of the last call
        self.pos: list[float] = []  # the robot's position at the last call (set by the first)
        self.rot: list[float] = []  # ... and its rotation, row-major

    def drive(self, c0: float, c1: float, c2: float, time: float, pos: list[float], rot: list[float],
              fraction: float, settle: int, heading: bool) -> tuple[float, float, float]:
        """What to drive the robot with for the command (c0, c1, c2), the robot at `pos` and `rot` at simulated
        `time`. The trim is corrected once the command has been held `settle` calls (what a robot still speeding
        up misses is no slip: counted, it would wind the trim up); `heading`: the turn rate is about the world's
        vertical (a ground robot's heading), else about the robot's own z axis."""
        previous, mark_time, mark_pos, mark_rot = self.command, self.time, self.pos, self.rot
        self.command, self.time, self.pos, self.rot = (c0, c1, c2), time, pos, rot
        t0, t1, t2 = self.trim
        if previous is None or (c0, c1, c2) != previous:  # the first call, or a new command
            self.held = 0
            if previous is not None:
                p0, p1, p2 = previous
                t0 = t0 if _sign(c0) == _sign(p0) else 0.0
                t1 = t1 if _sign(c1) == _sign(p1) else 0.0
                t2 = t2 if _sign(c2) == _sign(p2) else 0.0
                self.trim = (t0, t1, t2)
            return c0 + t0, c1 + t1, c2 + t2
        held = self.held = self.held + 1
        dt = time - mark_time
        if held >= settle and held >= 2 and dt > 0:  # the last interval ran under this command throughout
            v0, v1, v2 = mean_velocity(mark_pos, mark_rot, pos, rot, dt, heading)
            # each trim plus the gain's share of the error, clamped to +-limit (as min(max(t, -limit), limit))
            limit, t = LIMIT + fraction * abs(c0), t0 + GAIN * (c0 - v0)
            t = -limit if -limit > t else t
            t0 = limit if limit < t else t
            limit, t = LIMIT + fraction * abs(c1), t1 + GAIN * (c1 - v1)
            t = -limit if -limit > t else t
            t1 = limit if limit < t else t
            limit, t = LIMIT + fraction * abs(c2), t2 + GAIN * (c2 - v2)
            t = -limit if -limit > t else t
            t2 = limit if limit < t else t
            self.trim = (t0, t1, t2)
        return c0 + t0, c1 + t1, c2 + t2


def _sign(x: float) -> int:
    return (x > 0.0) - (x < 0.0)


def mean_velocity(pos0: list[float], rot0: list[float], pos1: list[float], rot1: list[float], dt: float,
                  heading: bool) -> tuple[float, float, float]:
    """(vx, vy, wz) of a body over an interval, from its poses at both ends (positions; rotations as row-major
    9-lists): velocity in its own frame, turn rate about its own z axis, or with `heading` about the world's
    vertical. Written out: the rotation between both ends is geometry's times_transpose or transpose_times, the
    same sums in the same order (tests/test_geometry.py)."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8 = rot0
    b0, b1, b2, b3, b4, b5, b6, b7, b8 = rot1
    if heading:  # rot1 rot0^T, in the world's frame
        d00, d11, d22 = b0 * a0 + b1 * a1 + b2 * a2, b3 * a3 + b4 * a4 + b5 * a5, b6 * a6 + b7 * a7 + b8 * a8
        d01, d02, d12 = b0 * a3 + b1 * a4 + b2 * a5, b0 * a6 + b1 * a7 + b2 * a8, b3 * a6 + b4 * a7 + b5 * a8
        d10, d20, d21 = b3 * a0 + b4 * a1 + b5 * a2, b6 * a0 + b7 * a1 + b8 * a2, b6 * a3 + b7 * a4 + b8 * a5
    else:  # rot0^T rot1, in the body's frame
        d00, d11, d22 = a0 * b0 + a3 * b3 + a6 * b6, a1 * b1 + a4 * b4 + a7 * b7, a2 * b2 + a5 * b5 + a8 * b8
        d01, d02, d12 = a0 * b1 + a3 * b4 + a6 * b7, a0 * b2 + a3 * b5 + a6 * b8, a1 * b2 + a4 * b5 + a7 * b8
        d10, d20, d21 = a1 * b0 + a4 * b3 + a7 * b6, a2 * b0 + a5 * b3 + a8 * b6, a2 * b1 + a5 * b4 + a8 * b7
    vx, vy, vz = (d21 - d12) / 2, (d02 - d20) / 2, (d10 - d01) / 2
    sin = math.sqrt(vx * vx + vy * vy + vz * vz)
    angle = math.atan2(sin, (d00 + d11 + d22 - 1.0) / 2.0)
    wz = vz * (angle / sin) if sin > 1e-12 else vz
    x, y, z = pos1[0] - pos0[0], pos1[1] - pos0[1], pos1[2] - pos0[2]
    # the linear velocity in the frame half-way through: the mean of the displacement in the frames at both ends
    # (transpose_apply's x and y, written out: z is not needed)
    return (((a0 * x + a3 * y + a6 * z) + (b0 * x + b3 * y + b6 * z)) / 2.0 / dt,
            ((a1 * x + a4 * y + a7 * z) + (b1 * x + b4 * y + b7 * z)) / 2.0 / dt, wz / dt)
