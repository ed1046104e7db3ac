"""Simulated time and the two time strategies: best_effort follows the wall clock (times a scale),
fixed_step runs as fast as the machine allows. Time advances by exactly 1/frequency per frame."""

from __future__ import annotations

import math
import time as _time

from morsec.constants import MAX_TIME_SCALE, MIN_TIME_SCALE

MAX_LAG = 0.25  # wall-clock seconds behind schedule before best_effort gives up catching up


class Clock:
    def __init__(self, frequency: float, strategy: str, scale: float, relative: bool):
        self.frequency = frequency
        self.dt = 1.0 / frequency
        self.strategy = strategy
        self.scale = time_scale(scale)
        self.origin = 0.0 if relative else _time.time()
        self.frames = 0
        self._wall_anchor = _time.perf_counter()
        self._sim_anchor = 0.0
        self._last_wall = self._wall_anchor
        self._n = 0
        self._mean = 0.0
        self._m2 = 0.0

    @property
    def elapsed(self) -> float:
        """Simulated seconds since the start."""
        return self.frames * self.dt

    def now(self) -> float:
        """The timestamp sensors publish: epoch-based unless relative time was asked for."""
        return self.origin + self.elapsed

    def tick(self) -> None:
        self.frames += 1
        wall = _time.perf_counter()
        sample = wall - self._last_wall
        self._last_wall = wall
        self._n += 1
        delta = sample - self._mean
        self._mean += delta / self._n
        self._m2 += delta * (sample - self._mean)

    def delay(self) -> float:
        """Wall-clock seconds to wait before the next frame (0 for fixed_step)."""
        if self.strategy != "best_effort":
            return 0.0
        target = self._wall_anchor + (self.elapsed - self._sim_anchor) / self.scale
        remaining = target - _time.perf_counter()
        if remaining < -MAX_LAG:  # too slow for real time: run on, do not burst to catch up
            self.restart()
            return 0.0
        return max(0.0, remaining)

    def set_scale(self, scale: float) -> None:
        self.scale = time_scale(scale)
        self.restart()

    def restart(self) -> None:
        self._wall_anchor = _time.perf_counter()
        self._sim_anchor = self.elapsed

    def statistics(self) -> dict:
        variance = self._m2 / (self._n - 1) if self._n > 1 else 0.0
        mean = self._mean
        return {
            "mean_time": mean,
            "variance_time": variance,
            "mean_frame_by_sec": (1.0 / mean) if mean > 0 else 0.0,
            "real_time_factor": (self.dt / mean) if mean > 0 else 0.0,
            "frames": self.frames,
            "simulated_time": self.elapsed,
        }


def time_scale(value) -> float:
    """A time scale within [MIN_TIME_SCALE, MAX_TIME_SCALE], else ValueError: a frame's wait, 1/frequency
    divided by the scale, stays a duration the wall clock can count."""
    scale = float(value)
    if not MIN_TIME_SCALE <= scale <= MAX_TIME_SCALE:  # NaN fails the comparison too
        raise ValueError(f"time scale must be a positive number from {MIN_TIME_SCALE:g} to {MAX_TIME_SCALE:g}, "
                         f"got {value!r}")
    return scale


class Periodic:
    """MORSE's periodic_call: a component ticks at its frequency in simulated time, at most once a
    frame, tolerating half a frame, without bursts after a pause."""

    def __init__(self, frequency: float, loop_dt: float):
        self.period = 1.0 / frequency
        self.tolerance = loop_dt / 2
        self.n = 0

    def due(self, t: float) -> bool:
        if t + self.tolerance < self.n * self.period:
            return False
        self.n = max(self.n + 1, math.floor((t + self.tolerance) / self.period) + 1)
        return True
