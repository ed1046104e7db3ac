"""Velocity actuators that set the robot's body velocity (motion_vw, motion_xyw) track their command as
MORSE's do: MORSE writes the velocity itself, so a turn held for 12 s ends where the arc says and a robot
sliding sideways goes as far as asked, whatever its wheels' friction against the ground, less only what
MORSE's Bullet ground friction took between two ticks (morsec.kits.ground_friction)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from morsec.kits import ground_friction
from morsec.testing import simulate

MU, G = ground_friction.ground_friction(None), 9.81
ATRV_DAMPING = 0.02  # the ATRV's Bullet damping (components/robots/atrv)


def morse_tick(vx: float, vy: float, w: float) -> tuple[float, float, float]:
    """What MORSE's robot made of (vx, vy, w) over a 60 Hz tick: its mean velocity, friction and damping
    taken off."""
    return ground_friction.turned(vx, vy, w, ground_friction.slide(vx, vy, MU, G, 1 / 60, 1 / 60, ATRV_DAMPING).mean)


def atrv(motion: str, objects: str = "", locks: str = "[]") -> str:
    return f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: robot
    type: atrv
    locks: {locks}
    components:
      - {{name: motion, type: {motion}}}
{objects}"""


def drive(h, seconds: float, **command) -> tuple[np.ndarray, float]:
    """Command, run `seconds`, stop, settle: (displacement x, y in the start frame, unwrapped yaw change)."""
    start, rot = h.body_pose("robot")
    yaws = [h.yaw("robot")]
    h.command("robot.motion", **command)
    for _ in range(round(seconds * 60)):
        h.step()
        yaws.append(h.yaw("robot"))
    h.command("robot.motion", **{k: 0.0 for k in command})
    for _ in range(30):
        h.step()
        yaws.append(h.yaw("robot"))
    end, _ = h.body_pose("robot")
    return (rot.T @ (end - start))[:2], float(np.unwrap(yaws)[-1] - yaws[0])


def test_motion_vw_long_turn_follows_the_arc(tmp_path):
    """MORSE's vw_testing circle: 12 s at v = 0.5, w = -pi/8 is three quarters of a circle of radius 4/pi.
    The ATRV's wheels skid sideways in a turn; their friction must not slow the turn (it did: 3.5 %)."""
    v, w, t = 0.5, -math.pi / 8, 12.0
    with simulate(atrv("motion_vw"), tmp_path) as h:
        h.run_for(0.3)
        moved, turned = drive(h, t, v=v, w=w)
    v, _, w = morse_tick(v, 0.0, w)  # 6 % slower, turning 2 % slower, as MORSE's ATRV
    assert turned == pytest.approx(w * t, abs=0.02)
    r = v / w
    assert moved == pytest.approx([r * math.sin(w * t), r * (1 - math.cos(w * t))], abs=0.03)


def test_motion_xyw_sideways_goes_as_far_as_asked(tmp_path):
    """MORSE's xyw_testing: 2 s at y = -1 m/s moves 2 m to the right, although the ATRV's wheels slide."""
    with simulate(atrv("motion_xyw"), tmp_path) as h:
        h.run_for(0.3)
        moved, turned = drive(h, 2.0, x=0.0, y=-1.0, w=0.0)
    assert moved == pytest.approx([0.0, 2.0 * morse_tick(0.0, -1.0, 0.0)[1]], abs=0.02)
    assert turned == pytest.approx(0.0, abs=0.01)


def test_motion_vw_against_a_wall_pushes_within_bounds(tmp_path):
    """A robot held by a wall does not wind its command up: the servos' targets stay within 25 % (+ 0.05)
    of the command, and it drives away at the commanded speed once turned back. (Roll and pitch locked:
    pushed that hard against a wall, an ATRV climbs it and tumbles.)"""
    crate = "objects:\n  - {name: wall, type: box, translate: [1.2, 0.0, 0.5], size: [0.4, 4.0, 1.0]}\n"
    with simulate(atrv("motion_vw", crate, locks="[rotation_x, rotation_y]"), tmp_path) as h:
        h.run_for(0.3)
        h.command("robot.motion", v=1.0, w=0.0)
        h.run_for(3.0)
        handle = h.sim.robots[0].handle
        ctrl = h.sim.data.ctrl[handle.servo]
        # pushing as hard as it may, no harder (the command: what MORSE's tick leaves of 1 m/s)
        assert ctrl[0] == pytest.approx(morse_tick(1.0, 0.0, 0.0)[0] * 1.25 + 0.05)
        assert h.body_pose("robot")[0][0] < 0.5  # the wall holds it
        moved, _ = drive(h, 1.0, v=-1.0, w=0.0)
    assert moved[0] == pytest.approx(-1.0, abs=0.05)


@pytest.mark.parametrize(("robot", "rate"), [("segwayrmp400", 1.16 / 1.2), ("pioneer3dx", 1.0)])
def test_motion_vw_diff_turns_steadily_at_w(robot, rate, tmp_path):
    """Wheels slip (a skid-steer Segway's in stick-slip: its turn rate swung from 0.72 w to 1.1 w): the
    wheels are asked what the robot missed, so it turns steadily, half a second after half a second, at w, or
    for the Segway at what MORSE's wheel speeds (FixTurningSpeed 1.16) made of w: 1.16 w / 1.2."""
    text = f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: robot
    type: {robot}
    components:
      - {{name: motion, type: motion_vw_diff}}
"""
    v, w = 1.0, -math.pi / 4
    with simulate(text, tmp_path) as h:
        h.run_for(0.3)
        h.command("robot.motion", v=v, w=w)
        h.run_for(0.5)
        yaws = [h.yaw("robot")]
        for _ in range(4 * 60):
            h.step()
            yaws.append(h.yaw("robot"))
    turned = np.unwrap(yaws)
    rates = np.diff(turned[::30]) * 2  # over each half second
    assert (turned[-1] - turned[0]) / 4 == pytest.approx(rate * w, rel=0.03)
    assert rates == pytest.approx([rate * w] * len(rates), rel=0.12)


def test_motion_vw_starts_and_stops_without_rocking(tmp_path):
    """MORSE sets the new velocity on the whole body at once; a servo pushing at the origin (below the
    centre of mass) to reach it pitched the ATRV by 1.4 degrees and lifted it 8 mm (MORSE's velocity_testing
    reads the angular velocity 0.1 s after a command: it found 0.39 rad/s of pitch)."""
    with simulate(atrv("motion_vw"), tmp_path) as h:
        h.run_for(0.3)
        z0 = h.body_pose("robot")[0][2]
        for v in (1.0, 0.0, -1.0, 0.0):
            h.command("robot.motion", v=v, w=0.0)
            for _ in range(30):
                h.step()
                pos, rot = h.body_pose("robot")
                assert abs(pos[2] - z0) < 0.002
                assert abs(math.asin(-rot[2, 0])) < math.radians(0.2)
