"""MORSE's Waypoint: drive a (non-holonomic) robot to a goal by turning and going forward.

Per tick, with d the distance from this actuator to the goal (planar unless FreeZ), e the heading error
(bearing of the goal minus the robot's yaw) and s the speed:

* d <= tolerance: status "Arrived", speed 0, a pending `goto` completes with SUCCESS "Arrived"; the
  robot then stays put (unless RemainAtDestination) until the goal changes;
* s == 0 (after `stop`): speed 0, status unchanged ("Stop");
* otherwise status "Transit"; yaw rate w = sign(e) * s/2 (bounded so that one tick does not overshoot;
  within AngleTolerance it decreases linearly to 0 as e -> 0); forward speed v = min(s, d * frequency),
  and v = 0 while |e| >= 60 degrees (the robot turns on the spot first);
* obstacle avoidance (ObstacleAvoidance): MORSE's two radars (Radar.L / Radar.R, 3 m) are two fans of rays
  cast with one `mj_multiRay` call from the actuator, horizontally, to the left and to the right of the
  robot's heading. A hit counts when it lies in the corridor the robot is about to sweep (ahead, within
  3 m, laterally within the robot's half width + 0.25 m) and nearer than the goal; the robot then turns
  away from the side whose obstacle is nearer at s/2, and stops going forward while that obstacle is
  less than 0.35 m ahead of its front. While going round an obstacle (one was in the corridor during the
  last 0.5 m driven, or one is within 0.3 m of the robot's footprint) the 60 degree rule is suspended:
  the robot keeps going forward along the obstacle instead of turning back towards it on the spot.
"""

from __future__ import annotations

import logging
import math

import mujoco
import numpy as np
from pydantic import Field

from morsec.component import Actuator, ControlTypeProperties, DataField, async_service, service
from morsec.kits.geometry import normalize_angle
from morsec.kits.markers import visual_marker
from morsec.modifiers.coordinates import POSITION_IN

log = logging.getLogger("morsec.actuators.waypoint")

TURN_ON_THE_SPOT = math.pi / 3  # v = 0 while the heading error is at least this
RADAR_RANGE = 3.0  # m, MORSE's radars
RADAR_FAN = math.radians(90.0)  # each fan spans 0 .. 90 degrees on its side of the heading
RADAR_STEP = math.radians(1.5)
CORRIDOR_MARGIN = 0.25  # m on each side of the robot
STOP_GAP = 0.35  # m between the robot's front and an obstacle: no forward motion below this
BYPASS = 0.5  # m driven forward after the last obstacle seen ahead before turning on the spot again
NEAR = 0.3  # m beyond the robot's footprint: an obstacle this close keeps the robot going round it
VISUAL_GROUP, HIDDEN_GROUP = 2, 5
RAY_MASK = np.array([0 if g in (VISUAL_GROUP, HIDDEN_GROUP) else 1 for g in range(mujoco.mjNGROUP)], dtype=np.uint8)


class Waypoint(Actuator):
    """Moves the robot towards a goal point by turning about z and going forward (MORSE's Waypoint), with
    statuses Arrived / Transit / Stop, an interruptible `goto` and ray-based obstacle avoidance."""

    short_descr = "Drive the robot to a goal point, turning then going forward"
    builder_name = "Waypoint"
    frequency = 60.0
    modifiers = POSITION_IN
    base_servo = True

    class Properties(ControlTypeProperties):
        ObstacleAvoidance: bool = Field(True, description="steer away from obstacles seen by the two radar fans")
        FreeZ: bool = Field(False, description="control z too (flying or underwater robots); else the distance "
                            "to the goal is planar")
        AngleTolerance: float = Field(math.radians(10), ge=0, description="heading error, rad, below which the "
                                      "robot turns slower and slower (no turn at 0)")
        Speed: float = Field(1.0, description="initial value of the `speed` field, m/s")
        Target: str = Field("", description="name of a scene object moved to the goal (a visual marker)")
        Ignore: str = Field("", description="comma-separated property names: objects having one are ignored by "
                            "the obstacle avoidance")
        RemainAtDestination: bool = Field(False, description="keep servoing to the goal after arrival (drive "
                                          "back if pushed away)")

    data = (
        DataField("x", 0.0, "float", "x of the goal, world frame, m (default: the actuator's initial position)"),
        DataField("y", 0.0, "float", "y of the goal, world frame, m"),
        DataField("z", 0.0, "float", "z of the goal, world frame, m (used only with FreeZ)"),
        DataField("tolerance", 0.5, "float", "distance, m, under which the goal is reached"),
        DataField("speed", 1.0, "float", "forward speed, m/s (initial value: the Speed property)"),
    )

    # ------------------------------------------------------------------ set up
    def start(self):
        x, y, z = (float(v) for v in self.position())
        self.local_data.update(x=x, y=y, z=z, speed=float(self.properties.Speed))
        self.status = "Arrived"
        self._previous_speed = 0.0
        self._arrived_at = self._goal_key()  # goal for which the robot arrived: do nothing until it changes
        self._target = None
        self._bypass = 0.0  # m still to go forward round an obstacle, whatever the heading error
        self._warned: set[str] = set()
        self._setup_radars()

    def _goal_key(self):
        d = self.local_data
        return (float(d["x"]), float(d["y"]), float(d["z"]), float(d["tolerance"]))

    def _setup_radars(self):
        m, d = self.sim.model, self.sim.data
        robot = self.robot
        own_bodies = np.array(robot.subtree())
        own = np.flatnonzero(np.isin(m.geom_bodyid, own_bodies) & (m.geom_group != VISUAL_GROUP))
        self._own = own
        # the robot's footprint in its own frame, relative to this actuator: front and half width
        base_pos, base_rot = robot.pose()
        me = base_rot.T @ (self.position() - base_pos)
        front, half_width = 0.1, 0.1
        for g in own:
            center, half = m.geom_aabb[g, :3], m.geom_aabb[g, 3:]
            signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], float)
            corners = d.geom_xpos[g] + (center + signs * half) @ d.geom_xmat[g].reshape(3, 3).T
            local = (corners - base_pos) @ base_rot - me
            front = max(front, float(local[:, 0].max()))
            half_width = max(half_width, float(np.abs(local[:, 1]).max()))
        self._front, self._half_width = front, half_width
        self._radius = math.hypot(front, half_width)
        self._cutoff = math.hypot(RADAR_RANGE, half_width + CORRIDOR_MARGIN)  # farthest hit that can matter
        # ray fans, left (positive angles) then right, in the robot's yaw frame
        left = np.arange(RADAR_STEP / 2, RADAR_FAN + 1e-9, RADAR_STEP)
        self._angles = np.concatenate([left, -left])
        self._dirs = np.stack([np.cos(self._angles), np.sin(self._angles), np.zeros_like(self._angles)], axis=1)
        self._vec = np.empty_like(self._dirs)
        self._geomid = np.empty(len(self._angles), dtype=np.int32)
        self._dist = np.empty(len(self._angles))
        # geoms never seen as obstacles: the ground (planes, height fields) and objects with an Ignore property
        ignore_props = [p.strip() for p in self.properties.Ignore.split(",") if p.strip()]
        ignored_bodies = []
        for obj in self.sim.objects:
            if obj.body_id >= 0 and any(p in obj.properties for p in ignore_props):
                ignored_bodies.append(obj.body_id)
        ignored = np.isin(m.body_rootid[m.geom_bodyid], ignored_bodies) if ignored_bodies else np.zeros(m.ngeom, bool)
        ground = np.isin(m.geom_type, [mujoco.mjtGeom.mjGEOM_PLANE, mujoco.mjtGeom.mjGEOM_HFIELD])
        self._not_obstacle = ignored | ground

    # ------------------------------------------------------------------ geometry
    def _distance(self, goal: np.ndarray) -> tuple[float, float]:
        """(distance used for arrival, planar distance) from the actuator to the goal."""
        delta = goal - self.position()
        planar = math.hypot(delta[0], delta[1])
        return (float(np.linalg.norm(delta)) if self.properties.FreeZ else planar), planar

    def radars(self, goal_distance: float) -> tuple[float, float, bool]:
        """Distances ahead (m, from the actuator) of the nearest obstacle in the robot's corridor on the left
        and on the right (inf: none), and whether an obstacle is close by on either side."""
        m, d = self.sim.model, self.sim.data
        _, rot = self.robot.pose()
        yaw = math.atan2(rot[1, 0], rot[0, 0])
        c, s = math.cos(yaw), math.sin(yaw)
        yaw_rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        np.matmul(self._dirs, yaw_rot.T, out=self._vec)
        saved = m.geom_group[self._own].copy()
        m.geom_group[self._own] = HIDDEN_GROUP
        try:
            mujoco.mj_multiRay(m, d, self.position().copy(), self._vec.reshape(-1), RAY_MASK, 1, -1, self._geomid,
                               self._dist, None, len(self._angles), self._cutoff)
        finally:
            m.geom_group[self._own] = saved
        hit = (self._dist >= 0) & (self._geomid >= 0)
        hit[hit] &= ~self._not_obstacle[self._geomid[hit]]
        ahead = self._dist * np.cos(self._angles)
        lateral = np.abs(self._dist * np.sin(self._angles))
        threat = hit & (ahead > 0) & (ahead <= RADAR_RANGE) & (lateral <= self._half_width + CORRIDOR_MARGIN) \
            & (self._dist < goal_distance)
        left = threat & (self._angles > 0)
        right = threat & (self._angles < 0)
        near = hit & (self._dist < self._radius + NEAR) & (self._dist < goal_distance)
        return (float(ahead[left].min()) if left.any() else math.inf,
                float(ahead[right].min()) if right.any() else math.inf, bool(near.any()))

    # ------------------------------------------------------------------ the tick
    def default_action(self):
        d = self.local_data
        goal = np.array([float(d["x"]), float(d["y"]), float(d["z"])])
        self._place_target(goal)
        control = self.properties.ControlType
        distance, planar = self._distance(goal)
        tolerance = float(d["tolerance"])
        speed = float(d["speed"])
        key = self._goal_key()

        if distance <= tolerance:
            self.status = "Arrived"
            self._arrived_at = key
            self.completed("SUCCESS", "Arrived")
            self.robot.apply_speed(control, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], self.frequency)
            return
        if key == self._arrived_at and not self.properties.RemainAtDestination and self.status == "Arrived":
            # arrived, then pushed away: stay put until a new goal comes (RemainAtDestination drives back)
            self.robot.apply_speed(control, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], self.frequency)
            return
        self._arrived_at = None
        if speed == 0:
            self.robot.apply_speed(control, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], self.frequency)
            return
        self.status = "Transit"

        _, rot = self.robot.pose()
        error = 0.0
        if planar > tolerance / 2:  # else the bearing of the goal is meaningless
            yaw = math.atan2(rot[1, 0], rot[0, 0])
            delta = goal - self.position()
            error = normalize_angle(math.atan2(delta[1], delta[0]) - yaw)
        turn = abs(speed) / 2
        step = abs(error) * self.frequency  # what would align the robot in one tick
        if abs(error) >= self.properties.AngleTolerance:
            w = math.copysign(min(turn, step), error)
        else:
            w = error / max(self.properties.AngleTolerance, 1e-9) * min(turn, step)
        v = min(speed, distance * self.frequency)
        if abs(error) >= TURN_ON_THE_SPOT:
            v = 0.0

        if self.properties.ObstacleAvoidance:
            left, right, near = self.radars(distance)
            nearest = min(left, right)
            if nearest < math.inf:
                self._bypass = BYPASS
            if near or self._bypass > 0:
                # going round an obstacle: keep moving along it even when the goal is far off the heading
                v = min(speed, distance * self.frequency)
            if nearest < math.inf:
                w = turn if right <= left else -turn  # away from the nearer side
                if nearest - self._front < STOP_GAP:
                    v = 0.0
            self._bypass = max(0.0, self._bypass - v / self.frequency)

        if self.properties.FreeZ:
            local = rot.T @ (goal - self.position())
            norm = float(np.linalg.norm(local)) or 1.0
            vx, vz = abs(v * local[0] / norm), v * local[2] / norm
        else:
            vx, vz = v, 0.0
        self.robot.apply_speed(control, [vx, 0.0, vz], [0.0, 0.0, w], self.frequency)

    def _place_target(self, goal: np.ndarray):
        name = self.properties.Target
        if not name:
            return
        if self._target is None:
            self._target = visual_marker(self.sim, name)  # MORSE's marker had NO_COLLISION: not in the way
            if self._target is None:
                if name not in self._warned:
                    self._warned.add(name)
                    log.warning("%s: Target %r is not a scene object", self.name, name)
                return
        self.sim.place_body(self._target, goal, np.eye(3))

    # ------------------------------------------------------------------ services
    def _set_goal(self, x, y, z, tolerance, speed):
        self.local_data.update(x=float(x), y=float(y), z=float(z), tolerance=float(tolerance), speed=float(speed))
        self._arrived_at = None

    @service
    def setdest(self, x: float, y: float, z: float, tolerance: float = 0.5, speed: float = 1.0) -> bool:
        """Set a new goal and return at once: False if the robot is already within `tolerance` of it (the
        goal is then not changed), else True."""
        distance, _ = self._distance(np.array([float(x), float(y), float(z)]))
        if distance <= float(tolerance):
            return False
        self._set_goal(x, y, z, tolerance, speed)
        return True

    @async_service(interruptible=True)
    def goto(self, x: float, y: float, z: float, tolerance: float = 0.5, speed: float = 1.0) -> None:
        """Go to (x, y, z); answers SUCCESS "Arrived" when there. Interruptible: a new `goto` preempts it,
        `cancel` aborts it (PREEMPTED) and the robot stops where it is."""
        self._set_goal(x, y, z, tolerance, speed)

    def interrupt(self) -> None:
        x, y, z = (float(v) for v in self.position())
        self.local_data.update(x=x, y=y, z=z, speed=0.0)
        self._arrived_at = None

    @service
    def stop(self) -> str:
        """Speed 0 until `resume`; the goal (and a pending `goto`) is kept. Returns the status, "Stop"."""
        if float(self.local_data["speed"]) != 0:
            self._previous_speed = float(self.local_data["speed"])
        self.local_data["speed"] = 0.0
        self.status = "Stop"
        return self.status

    @service
    def resume(self) -> str:
        """Restore the speed that `stop` saved and go on to the goal. Returns the status, "Transit"."""
        if self._previous_speed:
            self.local_data["speed"] = self._previous_speed
        self._previous_speed = 0.0
        self.status = "Transit"
        return self.status

    @service
    def get_status(self) -> str:
        """"Arrived", "Transit" or "Stop"."""
        return self.status


COMPONENT = Waypoint
