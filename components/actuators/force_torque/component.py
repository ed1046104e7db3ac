import numpy as np
from pydantic import Field

from morsec.component import Actuator, ComponentProperties, DataField


class ForceTorque(Actuator):
    """A force and a torque applied to the robot's body, re-applied until the next command, as MORSE's
    ForceTorque. With `RobotFrame` false (default), both are given in the actuator's frame and the force
    acts at the actuator's position (its lever arm adds a torque); with
    `RobotFrame` true, both are given in the robot's frame and act at its centre of mass. As MORSE's, the
    lever arm (the torque a force off-centre adds) is measured from the robot's origin, which in Blender
    was its centre of mass: an actuator at the origin pushes the robot without turning it.

    The wrench is MuJoCo's `xfrc_applied` on the robot's base body: it stays applied over the physics
    sub-steps, and adds up with the other force actuators of the robot (external_force, drag, ...)."""

    short_descr = "Force and torque applied to the robot"
    builder_name = "ForceTorque"
    frequency = 60.0

    class Properties(ComponentProperties):
        RobotFrame: bool = Field(False, description="true: force and torque in the robot's frame, at its centre "
                                 "of mass; false: in the actuator's frame, the force at the actuator's position")

    data = (
        DataField("force", [0.0, 0.0, 0.0], "vec3", "force along x, y, z, N"),
        DataField("torque", [0.0, 0.0, 0.0], "vec3", "torque around x, y, z, N m"),
    )

    def default_action(self):
        force = np.asarray(self.local_data["force"], float).reshape(3)
        torque = np.asarray(self.local_data["torque"], float).reshape(3)
        d = self.sim.data
        base = self.robot.body_id
        if self.properties.RobotFrame:
            rot = d.xmat[base].reshape(3, 3)
            self.robot.apply_wrench(self.name, rot @ force, rot @ torque)
            return
        rot = self.rotation()
        f_world = rot @ force
        # MORSE's lever arm: from the robot's origin (in Blender the centre of mass of the robot's body) to
        # the actuator; a ForceTorque at the origin pushes without turning the robot (apply_wrench puts the
        # force through the robot's centre of mass)
        lever = self.position() - d.xpos[base]
        self.robot.apply_wrench(self.name, f_world, rot @ torque + np.cross(lever, f_world))


COMPONENT = ForceTorque
