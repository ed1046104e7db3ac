from morsec.component import DataField, SampledSensor, body_position, body_rotation
from morsec.kits.geometry import euler_of_xmat
from morsec.modifiers.coordinates import POSITION_OUT
from morsec.modifiers.noise import PoseNoise


class Pose(SampledSensor):
    """World position and orientation of the sensor itself (not of the robot): mount it where you want
    the pose read. On an ATRV, `translate: [0, 0, -0.1]` reads the ground pose."""

    short_descr = "Position and orientation of the sensor, world frame"
    builder_name = "Pose"
    frequency = 60.0
    modifiers = {"noise": PoseNoise, "posenoise": PoseNoise, **POSITION_OUT}
    data = (
        DataField("x", 0.0, "float", "x coordinate of the sensor, world frame, m"),
        DataField("y", 0.0, "float", "y coordinate of the sensor, world frame, m"),
        DataField("z", 0.0, "float", "z coordinate of the sensor, world frame, m"),
        DataField("yaw", 0.0, "float", "rotation about z, rad: XYZ Euler angles of the sensor frame"),
        DataField("pitch", 0.0, "float", "rotation about y, rad"),
        DataField("roll", 0.0, "float", "rotation about x, rad"),
    )

    reads_body_poses = True

    def sample(self):
        return self.sim.body_poses,  # the frame's copy of the bodies' poses: this sensor's is read from it when needed

    def compute(self, poses):
        x, y, z = body_position(poses, self.body_id)
        roll, pitch, yaw = euler_of_xmat(body_rotation(poses, self.body_id))
        local = self.local_dict
        local["x"], local["y"], local["z"] = x, y, z
        local["yaw"], local["pitch"], local["roll"] = yaw, pitch, roll


COMPONENT = Pose
