"""MORSE's ground friction on a ground robot whose body velocity an actuator sets (MotionVW, MotionXYW,
Waypoint, Destination in 'Velocity' control).

MORSE set such a robot's velocity once per tick (`robot.apply_speed`, 60 Hz); Bullet then ran the tick's
physics sub-steps (2 per tick, MORSE's environments), in which the ground's Coulomb friction slowed the
body until the next tick set the velocity again. Each sub-step took mu g h off the planar speed (velocity
first, then position, as Bullet integrates), so over a tick the robot went at the command less
3/4 mu g / 60 along its direction of travel: 3 cm/s at the default friction, whatever the speed
(MORSE's `friction_testing`: 2 s at 1 m/s go 2.0 m at friction 0, 1.4 m at `set_friction(5)`). When no
actuator sets the velocity any more (MORSE's Waypoint once arrived or stopped), the robot slides on until
friction stops it: v^2 / (2 mu g), 0.2 m from 1 m/s.

The same friction, acting where the body touches the ground, also took a little of the yaw rate MORSE set
while the robot drove: how much depends on where Bullet's contact points fell under MORSE's bodies
(not known here: the robots' .blend files are not readable). MORSE's own tests measure it: its turning
robots lost about a third as large a share of their yaw rate as of their speed (TURN_SHARE; base/
vw_testing's and odometry_testing's 12 s circles close within their tolerances only so: with the yaw rate
kept they end 0.10 to 0.21 m off, with as large a share lost as of the speed 0.3 m off). Turning on the
spot (no speed) loses nothing.

mu is Bullet's combination of the two materials, their product: the robot's (`set_friction`, else
Blender's default 0.5) times the ground's (0.5: the material of MORSE's environments' ground, Blender's
default)."""

from __future__ import annotations

import math

BLENDER_FRICTION = 0.5  # Blender's default material friction: MORSE's ground, and a robot's unless set
BULLET_SUBSTEPS = 2  # Bullet's sub-steps per tick in MORSE's environments
TURN_SHARE = 1.0 / 3.0  # the share of the yaw rate lost, as a part of the share of the speed lost


def ground_friction(robot_friction: float | None) -> float:
    """Bullet's friction coefficient between a robot and MORSE's ground."""
    return (BLENDER_FRICTION if robot_friction is None else float(robot_friction)) * BLENDER_FRICTION


def slide(vx: float, vy: float, mu: float, gravity: float, duration: float,
          tick: float) -> tuple[tuple[float, float], tuple[float, float]]:
    """(mean, end) planar velocity (vx, vy) of a body set going at (vx, vy) and left to slide on the ground
    for `duration` s (the period of the actuator setting it; `tick` the simulation's tick, split in
    BULLET_SUBSTEPS sub-steps): friction mu g against the motion each sub-step, velocity updated before
    the position; it stops the body, never turns it back."""
    speed = math.hypot(vx, vy)
    if speed == 0.0 or mu <= 0.0 or duration <= 0.0:
        return (vx, vy), (vx, vy)
    h = tick / BULLET_SUBSTEPS
    steps = max(1, round(duration / h))
    loss = mu * gravity * h
    moved = 0.0
    s = speed
    for _ in range(steps):
        s = max(0.0, s - loss)
        moved += s * h
    mean = moved / (steps * h)
    ux, uy = vx / speed, vy / speed
    return (mean * ux, mean * uy), (s * ux, s * uy)


def turned(vx: float, vy: float, wz: float, mean: tuple[float, float]) -> tuple[float, float, float]:
    """(vx, vy, wz) over the period of a robot set going at (vx, vy, wz) whose planar velocity friction
    brought down to `mean` (see slide): the yaw rate loses TURN_SHARE of the share the speed lost."""
    speed = math.hypot(vx, vy)
    if speed == 0.0:
        return mean[0], mean[1], wz
    lost = 1.0 - math.hypot(*mean) / speed
    return mean[0], mean[1], wz * (1.0 - TURN_SHARE * lost)
