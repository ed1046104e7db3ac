from morsec.component import DataField, SampledSensor
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

    def start(self):
        # views of the sensor's world position and rotation in MjData (whose arrays stay put)
        self.xpos, self.xmat = self.sim.data.xpos[self.body_id], self.sim.data.xmat[self.body_id]

    def sample(self):
        return self.xpos.tolist(), self.xmat.tolist()

    def compute(self, pos, rot):
        x, y, z = pos
        roll, pitch, yaw = euler_of_xmat(rot)
        local = self.local_dict
        local["x"], local["y"], local["z"] = x, y, z
        local["yaw"], local["pitch"], local["roll"] = yaw, pitch, roll


COMPONENT = Pose
