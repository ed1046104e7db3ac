"""MORSE's Arucomarker: a virtual ArUco marker that a client moves about, to test marker tracking on the
pictures of a simulated camera.

The fields are the marker's pose as the ArUco library reports it, in its camera convention (x right,
y down, z forward): MORSE turns the translation into its own axes as (x, y, z)_morse = (z + xoffset,
x + yoffset, -y + zoffset) and the rotation into Euler angles (roll, pitch, yaw) applied in Blender's
"YZX" order, R = Rx(roll) Rz(yaw) Ry(pitch). MORSE adds the robot's world position to that translation
and uses the rotation as the world orientation; morsec does the same in the robot's frame (identical for
a robot that is not turned, and the marker stays in front of a camera of a turning robot).
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
from pydantic import Field

from morsec.component import Actuator, ComponentProperties, DataField, service
from morsec.kits.geometry import matrix_to_quat


def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def _ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def marker_rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Blender Euler (roll, pitch, yaw) in order "YZX": pitch about y first, then yaw about z, then roll about x."""
    return _rx(roll) @ _rz(yaw) @ _ry(pitch)


def marker_euler(r: np.ndarray) -> tuple[float, float, float]:
    """(roll, pitch, yaw) of `marker_rotation` for a rotation matrix."""
    yaw = math.asin(max(-1.0, min(1.0, -r[0, 1])))
    return math.atan2(r[2, 1], r[1, 1]), math.atan2(r[0, 2], r[0, 0]), yaw


class Arucomarker(Actuator):
    """A 0.1 m ArUco-style marker (facing its -x axis) placed at the pose of its fields, relative to the
    robot: position (z + xoffset, x + yoffset, -y + zoffset) in the robot's frame, rotation
    Rx(roll) Rz(yaw) Ry(pitch) (MORSE's conversion from the ArUco camera convention). The fields start at
    the values that keep the marker where the scene put it."""

    short_descr = "A virtual ArUco marker moved by a client"
    builder_name = "Arucomarker"
    frequency = 60.0

    class Properties(ComponentProperties):
        xoffset: float = Field(0.0, description="static offset added along the robot's x axis, m (align the marker "
                               "with a camera)")
        yoffset: float = Field(0.0, description="offset added along the robot's y axis, m")
        zoffset: float = Field(0.0, description="offset added along the robot's z axis, m")

    data = (
        DataField("x", 0.0, "float", "ArUco x (right): the marker goes to robot y = x + yoffset, m"),
        DataField("y", 0.0, "float", "ArUco y (down): the marker goes to robot z = -y + zoffset, m"),
        DataField("z", 0.0, "float", "ArUco z (forward): the marker goes to robot x = z + xoffset, m"),
        DataField("roll", 0.0, "float", "rotation about x, rad (applied last, Blender order YZX)"),
        DataField("pitch", 0.0, "float", "rotation about y, rad (applied first)"),
        DataField("yaw", 0.0, "float", "rotation about z, rad (applied second)"),
    )

    def start(self):
        p = self.properties
        base_pos, base_rot = self.robot.pose()
        rel = base_rot.T @ (self.position() - base_pos)
        roll, pitch, yaw = marker_euler(base_rot.T @ self.rotation())
        self.local_data.update(x=float(rel[1] - p.yoffset), y=float(p.zoffset - rel[2]),
                               z=float(rel[0] - p.xoffset), roll=roll, pitch=pitch, yaw=yaw)
        self._parent = int(self.sim.model.body_parentid[self.body_id])

    def target(self) -> tuple[np.ndarray, np.ndarray]:
        """The world pose the fields ask for."""
        d, p = self.local_data, self.properties
        rel = np.array([float(d["z"]) + p.xoffset, float(d["x"]) + p.yoffset, -float(d["y"]) + p.zoffset])
        rot = marker_rotation(float(d["roll"]), float(d["pitch"]), float(d["yaw"]))
        base_pos, base_rot = self.robot.pose()
        return base_pos + base_rot @ rel, base_rot @ rot

    def default_action(self):
        m, d = self.sim.model, self.sim.data
        pos, rot = self.target()
        parent_rot = d.xmat[self._parent].reshape(3, 3)
        m.body_pos[self.body_id] = parent_rot.T @ (pos - d.xpos[self._parent])
        m.body_quat[self.body_id] = matrix_to_quat(parent_rot.T @ rot)
        mujoco.mj_kinematics(m, d)

    # ------------------------------------------------------------------ MORSE's services
    @service
    def get_local_position(self) -> list[float]:
        """The marker's position in its parent's frame (the robot, or the component it is appended to), m."""
        return [float(v) for v in self.sim.model.body_pos[self.body_id]]

    @service
    def get_world_position(self) -> list[float]:
        """The marker's position in the world, m."""
        return [float(v) for v in self.position()]

    @service
    def get_local_orientation(self) -> list[list[float]]:
        """The marker's rotation matrix in its parent's frame (rows)."""
        parent_rot = self.sim.data.xmat[self._parent].reshape(3, 3)
        return (parent_rot.T @ self.rotation()).tolist()

    @service
    def get_world_orientation(self) -> list[list[float]]:
        """The marker's rotation matrix in the world (rows)."""
        return self.rotation().tolist()


COMPONENT = Arucomarker
