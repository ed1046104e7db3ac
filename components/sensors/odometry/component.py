import math

from morsec.component import DataField, Level, SampledSensor, body_position, body_rotation
from morsec.kits.geometry import (
    euler_of_transpose_times,
    normalize_angle,
    transpose_apply,
)
from morsec.modifiers.noise import OdometryNoise, PoseNoise


class Odometry(SampledSensor):
    """Odometry of the sensor, at three levels of integration. Frames are the sensor's **initial**
    pose: the integrated level starts at 0 whatever the robot's start pose (as ROS's `odom`)."""

    short_descr = "Odometry: distance, deltas or integrated pose and velocities"
    builder_name = "Odometry"
    frequency = 60.0
    modifiers = {"noise": PoseNoise, "posenoise": PoseNoise, "odometrynoise": OdometryNoise}
    levels = (
        Level("raw", "RawOdometry", "distance travelled since the previous tick"),
        Level("differential", None, "position and angle deltas since the previous tick, in the initial sensor "
              "frame"),
        Level("integrated", "IntegratedOdometry", "pose relative to the initial pose, and velocities", default=True),
    )
    data = (
        DataField("dS", 0.0, "float", "3D distance travelled since the previous tick, m", level="raw"),
        DataField("dx", 0.0, "float", "delta of x since the previous tick, initial sensor frame, m",
                  level="differential"),
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
        DataField("vx", 0.0, "float", "linear velocity along x of the sensor frame, m/s: the previous -> current "
                  "transform, in the previous sensor frame, x the nominal frequency", level="integrated"),
        DataField("vy", 0.0, "float", "linear velocity along y of the sensor frame, m/s", level="integrated"),
        DataField("vz", 0.0, "float", "linear velocity along z of the sensor frame, m/s", level="integrated"),
        DataField("wz", 0.0, "float", "angular velocity about z, rad/s", level="integrated"),
        DataField("wy", 0.0, "float", "angular velocity about y, rad/s", level="integrated"),
        DataField("wx", 0.0, "float", "angular velocity about x, rad/s", level="integrated"),
    )

    # Poses are plain floats (position 3-tuple, row-major rotation 9-tuple): 3x3 numpy products cost more than the
    # arithmetic itself. A tick keeps the frame's copy of the bodies' poses (Simulation.body_poses) and the one
    # of the tick before; the sensor's own pose in each is read when its data is computed.
    reads_body_poses = True

    def start(self):
        self.previous = self.sim.copy_body_poses()
        self.origin_pos, self.origin_rot = self._pose(self.previous)

    def _pose(self, poses):
        return body_position(poses, self.body_id), body_rotation(poses, self.body_id)

    def sample(self):
        """The bodies' poses at the last tick and at this one (the sensor's data is computed from both)."""
        previous, self.previous = self.previous, self.sim.body_poses
        return previous, self.previous

    def compute(self, previous, poses):
        self.compute_poses(*self._pose(previous), *self._pose(poses))

    def compute_poses(self, prev_pos, prev_rot, pos, rot):
        dx, dy, dz = transpose_apply(self.origin_rot, (pos[0] - prev_pos[0], pos[1] - prev_pos[1],
                                                        pos[2] - prev_pos[2]))
        r0, p0, y0 = euler_of_transpose_times(self.origin_rot, prev_rot)
        r1, p1, y1 = euler_of_transpose_times(self.origin_rot, rot)
        self.local_dict.update(dx=dx, dy=dy, dz=dz, dyaw=normalize_angle(y1 - y0),
                               dpitch=normalize_angle(p1 - p0), droll=normalize_angle(r1 - r0))


class RawOdometry(Odometry):
    def compute_poses(self, prev_pos, prev_rot, pos, rot):
        self.local_dict["dS"] = math.dist(pos, prev_pos)


class IntegratedOdometry(Odometry):
    def compute_poses(self, prev_pos, prev_rot, pos, rot):
        o, origin_rot = self.origin_pos, self.origin_rot
        px, py, pz = pos
        x, y, z = transpose_apply(origin_rot, (px - o[0], py - o[1], pz - o[2]))
        roll, pitch, yaw = euler_of_transpose_times(origin_rot, rot)
        # velocities: the previous->current transform in the previous sensor frame, times the nominal rate
        f = self.frequency
        vx, vy, vz = transpose_apply(prev_rot, (px - prev_pos[0], py - prev_pos[1], pz - prev_pos[2]))
        d_roll, d_pitch, d_yaw = euler_of_transpose_times(prev_rot, rot)
        local = self.local_dict
        local["x"], local["y"], local["z"] = x, y, z
        local["yaw"], local["pitch"], local["roll"] = yaw, pitch, roll
        local["vx"], local["vy"], local["vz"] = vx * f, vy * f, vz * f
        local["wz"], local["wy"], local["wx"] = d_yaw * f, d_pitch * f, d_roll * f


COMPONENT = Odometry
