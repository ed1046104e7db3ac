"""Simulated time and the two time strategies: best_effort follows the wall clock (times a scale),
fixed_step runs as fast as the machine allows, except between two sleeps of a client that paces itself
with `time sleep`, or after a command (SleepHold). Time advances by exactly 1/frequency per frame."""

from __future__ import annotations

import logging
import math
import time as _time
from typing import Any

from morsec.constants import MAX_TIME_SCALE, MIN_TIME_SCALE

log = logging.getLogger("morsec.time")

MAX_LAG = 0.25  # wall-clock seconds behind schedule before best_effort gives up catching up


class Clock:
    def __init__(self, frequency: float, strategy: str, scale: float, relative: bool):
        self.frequency = frequency
        self.dt = 1.0 / frequency
        self.strategy = strategy
        self.scale = time_scale(scale)
        self.origin = 0.0 if relative else _time.time()
        self.frames = 0
        self.elapsed = 0.0  # simulated seconds since the start: frames * dt (an attribute: read many times a frame)
        self._wall_anchor = _time.perf_counter()
        self._sim_anchor = 0.0
        self.paced = False  # fixed_step following the wall clock for now (delay() sets it)
        # the frames' wall-clock durations, for `time statistics`: from the first start of one to the last end,
        # and the sum of their squares (a tick adds one square: the mean and variance follow)
        self._first_wall = self._last_wall = self._wall_anchor
        self._squares = 0.0

    def now(self) -> float:
        """The timestamp sensors publish: epoch-based unless relative time was asked for."""
        return self.origin + self.elapsed

    def tick(self) -> None:
        frames = self.frames = self.frames + 1
        self.elapsed = frames * self.dt
        wall = _time.perf_counter()
        sample = wall - self._last_wall
        self._last_wall = wall
        self._squares += sample * sample

    def delay(self, paced: bool = False) -> float:
        """Wall-clock seconds to wait before the next frame: 0 for fixed_step, unless `paced` (a client is
        between two sleeps, SleepHold): then as in best_effort, but never catching up (the loop may have
        stood still, waiting for a client: those frames are not owed)."""
        lag = MAX_LAG
        if self.strategy != "best_effort":
            if not paced:
                self.paced = False
                return 0.0
            if not self.paced:  # from this frame on: the next one a frame's time later
                self.paced = True
                self.restart_a_frame_later()
            lag = 0.0
        target = self._wall_anchor + (self.elapsed - self._sim_anchor) / self.scale
        remaining = target - _time.perf_counter()
        if remaining < -lag:  # too slow for real time: run on, do not burst to catch up
            self.restart()
            return 0.0
        return max(0.0, remaining)

    def spare(self, paced: bool = False) -> float:
        """Wall-clock seconds until the next frame is due, as `delay` would wait them, read without moving
        the schedule: 0 when fixed_step runs as fast as it can."""
        if self.strategy != "best_effort":
            if not paced:
                return 0.0
            if not self.paced:  # delay() will put the next frame a frame's time from now
                return self.dt / self.scale
        target = self._wall_anchor + (self.elapsed - self._sim_anchor) / self.scale
        return max(0.0, target - _time.perf_counter())

    def set_scale(self, scale: float) -> None:
        self.scale = time_scale(scale)
        self.restart()

    def restart(self) -> None:
        """The wall clock's pace from now: the next frame at once (it takes the loop from now on)."""
        self._wall_anchor = _time.perf_counter()
        self._sim_anchor = self.elapsed

    def restart_a_frame_later(self) -> None:
        """The wall clock's pace from now, the next frame a frame's time from now."""
        self.restart()
        self._sim_anchor -= self.dt

    def statistics(self) -> dict:
        n = self.frames
        mean = (self._last_wall - self._first_wall) / n if n else 0.0
        variance = max(0.0, self._squares - n * mean * mean) / (n - 1) if n > 1 else 0.0
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
        # due at every frame, whatever n (due's test is then never true: the loop asks due only of the
        # others). Exact for period == loop_dt: n * period is then a time the clock reached (frames * dt)
        self.every_frame = self.period == loop_dt

    def due(self, t: float) -> bool:
        if t + self.tolerance < self.n * self.period:
            return False
        self.n = max(self.n + 1, math.floor((t + self.tolerance) / self.period) + 1)
        return True


# SleepHold's stand-in for the unknown sender of a message to an actuator stream
STREAM_COMMANDS = "messages to actuator streams"


class SleepHold:
    """fixed_step and the clients that pace themselves with `time sleep`: while such a client sleeps the
    loop runs as fast as it can; once its last running sleep has ended (`arm`), and until its next sleep
    starts (`release`), the loop runs as in best_effort (at the clock's scale), so that what the client
    does between two sleeps takes about as much simulated time as it would in best_effort: a round trip of
    the network, not a hundred frames. So does a client's first request, until its first sleep (`greet`).
    A command from a client with no sleep running (`wake`), and a
    message to an actuator stream, whose sender cannot be told (STREAM_COMMANDS), start the same phase,
    `wait` at most: `publish(cmd); sleep(t)` then means what it means in best_effort.

    The phase is bounded in wall-clock time, by `grace` from the end of the sleep: then the loop runs as
    fast as it can again; a client that sleeps and says nothing slows the others down for `grace`, no
    more. A client leaving (`forget`) ends it too. A new connection to an actuator stream is waited for,
    without stepping, until its first message arrives, `wait` at most (`stream_opened`)."""

    def __init__(self, wait: float, grace: float):
        self.wait = wait
        self.grace = grace
        self.opened: dict[Any, float] = {}  # new actuator stream connection -> deadline of the wait for its message
        self.opened_quiet_until = 0.0  # wall clock: no new connection is waited for before (one ran out)
        self.awake: dict[Any, float] = {}  # client -> wall-clock deadline of its best_effort phase
        self.greeted: set[Any] = set()  # clients whose first request came
        self.slept: set[Any] = set()  # clients in awake because their last sleep ended
        self.holds = 0  # for `time statistics`: sleeps that ended so
        self.overtime = 0  # ... best_effort phases that ran out

    def arm(self, client: Any) -> None:
        """The client's last running sleep ended."""
        if client is None or client in self.slept:
            return
        self.awake[client] = max(self.awake.get(client, 0.0), _time.perf_counter() + self.grace)
        self.slept.add(client)
        self.holds += 1

    def greet(self, client: Any) -> None:
        """The client's first request: until its first sleep starts, the loop follows the wall clock, `grace`
        at most (what it does before its first sleep, read a stream, send a command, takes the simulated time
        it would in best_effort)."""
        if client is not None and client not in self.greeted:
            self.greeted.add(client)
            self.wake(client, self.grace)

    def wake(self, client: Any, seconds: float) -> None:
        """The client, with no sleep running, sent a command: the loop follows the wall clock until its
        next sleep starts, for `seconds` at most (a running phase may last longer, not shorter)."""
        if client is not None:
            self.awake[client] = max(self.awake.get(client, 0.0), _time.perf_counter() + seconds)

    def stream_opened(self, connection: Any) -> None:
        """A client connected to an actuator stream: its first message is probably on its way (pymorse
        connects a stream when it is first used, and its message leaves a few milliseconds after the
        request that follows it on the service connection). The loop waits for it, `wait` at most; after
        such a wait ran out, connections opened within `grace` are not waited for (connecting again and
        again cannot stop the loop)."""
        now = _time.perf_counter()
        if now >= self.opened_quiet_until:
            self.opened[connection] = now + self.wait

    def stream_heard(self, connection: Any) -> None:
        """A message arrived on an actuator stream: a command, whose sender's sleep may follow."""
        self.opened.pop(connection, None)
        self.wake(STREAM_COMMANDS, self.wait)

    def stream_closed(self, connection: Any) -> None:
        self.opened.pop(connection, None)

    def release(self, client: Any) -> None:
        """The client's next sleep started (it may be the sender of the last stream command too)."""
        self.awake.pop(client, None)
        self.slept.discard(client)
        self.awake.pop(STREAM_COMMANDS, None)

    def forget(self, client: Any) -> None:
        """The client left."""
        self.awake.pop(client, None)
        self.slept.discard(client)
        self.greeted.discard(client)

    def holding(self) -> float:
        """Wall-clock seconds the loop still waits (without stepping) for a new stream's first message; 0:
        none."""
        if not self.opened:
            return 0.0
        now = _time.perf_counter()
        for connection, deadline in list(self.opened.items()):
            if deadline <= now:
                del self.opened[connection]
                self.opened_quiet_until = now + self.grace
        return min(self.opened.values()) - now if self.opened else 0.0

    def pacing(self) -> bool:
        """Whether some client is between two sleeps: the loop follows the wall clock."""
        if not self.awake:
            return False
        now = _time.perf_counter()
        for client, deadline in list(self.awake.items()):
            if deadline <= now:
                del self.awake[client]
                if client not in self.slept:  # a command, or a first request, with no sleep after it
                    continue
                self.slept.discard(client)
                self.overtime += 1
                log.info("a client did not ask for its next sleep within %g s after its time sleep ended: "
                         "the simulation runs as fast as it can again", self.grace)
        return bool(self.awake)


class Numbering:
    """The requests numbered 0, 1, 2 ... (pymorse's ids, morsec.client's) a client sent: which arrived, and
    when (simulated and wall-clock time) the last few did. From the first number seen on; numbers below it
    count as arrived."""

    MAX_AHEAD = 1000  # numbers arrived ahead of a missing one: beyond, the client does not number that way
    KEPT = 16  # arrival times kept, of the highest numbers

    def __init__(self, first: int):
        self.next = first  # every number below arrived
        self.ahead: set[int] = set()  # arrived, above a missing one
        # number -> (simulated s, wall-clock s) it arrived at, whether it was a command (to a component)
        self.arrivals: dict[int, tuple[float, float, bool]] = {}

    def saw(self, number: int, simulated: float, wall: float, command: bool) -> bool:
        """Record an arrival; False when the client's ids are not such a sequence after all."""
        if number == self.next:
            self.next += 1
            while self.next in self.ahead:
                self.ahead.remove(self.next)
                self.next += 1
        elif number > self.next:
            self.ahead.add(number)
        self.arrivals[number] = (simulated, wall, command)
        if len(self.arrivals) > 2 * self.KEPT:
            newest = sorted(self.arrivals)[-self.KEPT:]
            self.arrivals = {n: self.arrivals[n] for n in newest}
        return len(self.ahead) <= self.MAX_AHEAD

    def all_before(self, number: int) -> bool:
        return self.next >= number


def request_number(request_id: str) -> int | None:
    """A request id that is a number (pymorse counts its requests from 0), else None."""
    return int(request_id) if request_id.isdigit() and len(request_id) <= 12 else None
