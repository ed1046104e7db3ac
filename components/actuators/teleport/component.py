import numpy as np

from morsec.component import Actuator, DataField, service
from morsec.kits.geometry import euler_to_quat, quat_to_matrix
from morsec.modifiers.coordinates import POSITION_IN


class Teleport(Actuator):
    """Moves the robot so that this actuator's frame is at the commanded world pose, every tick
    (dynamics of the robot are suspended: its velocity is zeroed, and the physics step of the frame does
    not move it, so that its sensors read the pose it was put at, as MORSE's read it before Blender's
    physics step: gravity does not pull it down, the ground does not push a robot put below it)."""

    short_descr = "Place the robot at a pose"
    builder_name = "Teleport"
    frequency = 60.0
    modifiers = {name: m for name, m in POSITION_IN.items() if name != "utm"}  # no utm, as MORSE
    data = (
        DataField("x", 0.0, "float", "x of the actuator frame, world frame, m (default: its initial pose)"),
        DataField("y", 0.0, "float", "y of the actuator frame, world frame, m"),
        DataField("z", 0.0, "float", "z of the actuator frame, world frame, m"),
        DataField("roll", 0.0, "float", "rotation about x, rad (XYZ Euler angles of the actuator frame)"),
        DataField("pitch", 0.0, "float", "rotation about y, rad"),
        DataField("yaw", 0.0, "float", "rotation about z, rad"),
    )

    _placed: tuple | None = None  # the last command applied, and the robot's qpos it gave
    _placed_qpos: np.ndarray | None = None
    _rigid = False  # see start

    def start(self):
        # a free robot whose base carries this frame with no joint between: a robot at the qpos a command
        # gave is at that command
        m, body = self.sim.model, self.body_id
        while body != self.robot.body_id and body > 0 and m.body_jntnum[body] == 0:
            body = int(m.body_parentid[body])
        self._rigid = self.robot.free and body == self.robot.body_id
        x, y, z = self.position()
        roll, pitch, yaw = self.euler()
        self.local_data.update(x=x, y=y, z=z, roll=roll, pitch=pitch, yaw=yaw)

    def reset(self):
        self.start()  # the command goes back to the (restored) initial pose

    def default_action(self):
        d = self.local_data
        command = (d["x"], d["y"], d["z"], d["roll"], d["pitch"], d["yaw"])
        robot = self.robot
        if self._rigid and command == self._placed and np.array_equal(robot.base_qpos(), self._placed_qpos):
            robot.stop()  # where the same command put it (pinned since): no need to compute the pose again
            self.sim.pin(robot.body_id)
            return
        target_rot = quat_to_matrix(euler_to_quat(float(d["roll"]), float(d["pitch"]), float(d["yaw"])))
        target_pos = np.array([float(d["x"]), float(d["y"]), float(d["z"])])
        robot.place_frame(self.body_id, target_pos, target_rot)
        self.sim.pin(robot.body_id)  # physics does not move it before the sensors read it
        if self._rigid:
            self._placed, self._placed_qpos = command, robot.base_qpos().copy()

    @service
    def translate(self, x: float, y: float = 0.0, z: float = 0.0):
        """Move by (x, y, z) metres, world frame, relative to the current command."""
        self.local_data["x"] = float(self.local_data["x"]) + float(x)
        self.local_data["y"] = float(self.local_data["y"]) + float(y)
        self.local_data["z"] = float(self.local_data["z"]) + float(z)

    @service
    def rotate(self, roll: float, pitch: float = 0.0, yaw: float = 0.0):
        """Rotate by (roll, pitch, yaw) radians, relative to the current command."""
        self.local_data["roll"] = float(self.local_data["roll"]) + float(roll)
        self.local_data["pitch"] = float(self.local_data["pitch"]) + float(pitch)
        self.local_data["yaw"] = float(self.local_data["yaw"]) + float(yaw)


COMPONENT = Teleport
