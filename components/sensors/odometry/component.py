import math

import numpy as np

from morsec.component import DataField, Level, Sensor
from morsec.geometry import matrix_to_euler, normalize_angle

FIELDS_DIFF = ("dx", "dy", "dz", "dyaw", "dpitch", "droll")
FIELDS_INT = ("x", "y", "z", "yaw", "pitch", "roll", "vx", "vy", "vz", "wz", "wy", "wx")


class Odometry(Sensor):
    """Odometry of the sensor, at three levels of integration. Frames are the sensor's **initial**
    pose: the integrated level starts at 0 whatever the robot's start pose (as ROS's `odom`)."""

    short_descr = "Odometry: distance, deltas or integrated pose and velocities"
    builder_name = "Odometry"
    frequency = 60.0
    levels = (
        Level("raw", "RawOdometry", "distance travelled since the previous tick"),
        Level("differential", None, "position and angle deltas since the previous tick"),
        Level("integrated", "IntegratedOdometry", "pose and velocities in the initial sensor frame", default=True),
    )
    data = (
        DataField("dS", 0.0, "float", "3D distance travelled since the previous tick, m", level="raw"),
        DataField("dx", 0.0, "float", "delta of x since the previous tick, initial sensor frame, m", level="differential"),
        DataField("dy", 0.0, "float", "delta of y, m", level="differential"),
        DataField("dz", 0.0, "float", "delta of z, m", level="differential"),
        DataField("dyaw", 0.0, "float", "delta of yaw, rad, normalised to [-pi, pi)", level="differential"),
        DataField("dpitch", 0.0, "float", "delta of pitch, rad", level="differential"),
        DataField("droll", 0.0, "float", "delta of roll, rad", level="differential"),
        DataField("x", 0.0, "float", "x in the initial sensor frame, m", level="integrated"),
        DataField("y", 0.0, "float", "y in the initial sensor frame, m", level="integrated"),
        DataField("z", 0.0, "float", "z in the initial sensor frame, m", level="integrated"),
        DataField("yaw", 0.0, "float", "yaw relative to the initial orientation, rad", level="integrated"),
        DataField("pitch", 0.0, "float", "pitch relative to the initial orientation, rad", level="integrated"),
        DataField("roll", 0.0, "float", "roll relative to the initial orientation, rad", level="integrated"),
        DataField("vx", 0.0, "float", "linear velocity along x of the sensor frame, m/s", level="integrated"),
        DataField("vy", 0.0, "float", "linear velocity along y of the sensor frame, m/s", level="integrated"),
        DataField("vz", 0.0, "float", "linear velocity along z of the sensor frame, m/s", level="integrated"),
        DataField("wz", 0.0, "float", "angular velocity about z, rad/s", level="integrated"),
        DataField("wy", 0.0, "float", "angular velocity about y, rad/s", level="integrated"),
        DataField("wx", 0.0, "float", "angular velocity about x, rad/s", level="integrated"),
    )

    def start(self):
        self.origin_pos = self.position().copy()
        self.origin_rot = self.rotation().copy()
        self.previous_pos = self.origin_pos.copy()
        self.previous_rot = self.origin_rot.copy()

    def relative(self):
        """Current pose in the initial sensor frame: position and rotation matrix."""
        pos = self.origin_rot.T @ (self.position() - self.origin_pos)
        rot = self.origin_rot.T @ self.rotation()
        return pos, rot

    def advance(self):
        pos, rot = self.position().copy(), self.rotation().copy()
        prev_pos, prev_rot = self.previous_pos, self.previous_rot
        self.previous_pos, self.previous_rot = pos, rot
        return prev_pos, prev_rot, pos, rot

    def default_action(self):
        prev_pos, prev_rot, pos, rot = self.advance()
        delta = self.origin_rot.T @ (pos - prev_pos)
        r0, p0, y0 = matrix_to_euler(self.origin_rot.T @ prev_rot)
        r1, p1, y1 = matrix_to_euler(self.origin_rot.T @ rot)
        self.local_data.update(dx=float(delta[0]), dy=float(delta[1]), dz=float(delta[2]), dyaw=normalize_angle(y1 - y0),
                               dpitch=normalize_angle(p1 - p0), droll=normalize_angle(r1 - r0))


class RawOdometry(Odometry):
    def default_action(self):
        prev_pos, _, pos, _ = self.advance()
        self.local_data["dS"] = float(np.linalg.norm(pos - prev_pos))


class IntegratedOdometry(Odometry):
    def default_action(self):
        prev_pos, prev_rot, pos, rot = self.advance()
        rel_pos, rel_rot = self.relative()
        roll, pitch, yaw = matrix_to_euler(rel_rot)
        # velocities: the previous->current transform in the previous sensor frame, times the nominal rate
        f = self.frequency
        v = prev_rot.T @ (pos - prev_pos) * f
        d_roll, d_pitch, d_yaw = matrix_to_euler(prev_rot.T @ rot)
        self.local_data.update(x=float(rel_pos[0]), y=float(rel_pos[1]), z=float(rel_pos[2]), yaw=yaw, pitch=pitch,
                               roll=roll, vx=float(v[0]), vy=float(v[1]), vz=float(v[2]), wz=d_yaw * f, wy=d_pitch * f,
                               wx=d_roll * f)


COMPONENT = Odometry
