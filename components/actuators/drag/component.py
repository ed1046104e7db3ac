import mujoco
import numpy as np
from pydantic import Field

from morsec.component import Actuator, ComponentProperties


class Drag(Actuator):
    """The drag force (fluid resistance) on the robot, as MORSE's Drag: along each axis of the robot's
    frame, F = -sign(v) v^2 DragCoeff, v the robot's velocity along that axis. The coefficients
    aggregate 0.5 rho A Cd (fluid density, cross-section, drag coefficient). Not controllable: no
    data, no stream. The force adds up with the robot's other force actuators (MuJoCo `xfrc_applied`)
    and is recomputed at the actuator's frequency."""

    short_descr = "Drag force opposing the robot's velocity"
    builder_name = "Drag"
    frequency = 60.0
    exportable = False

    class Properties(ComponentProperties):
        DragCoeffX: float = Field(0.09, description="aggregated drag coefficient along the robot's x axis, N s^2/m^2")
        DragCoeffY: float = Field(0.09, description="aggregated drag coefficient along the robot's y axis, N s^2/m^2")
        DragCoeffZ: float = Field(0.5, description="aggregated drag coefficient along the robot's z axis, N s^2/m^2")

    data = ()

    def default_action(self):
        m, d = self.sim.model, self.sim.data
        base = self.robot.body_id
        vel = np.zeros(6)
        # world frame (a body's "local" frame in mj_objectVelocity is its principal axes of inertia)
        mujoco.mj_objectVelocity(m, d, mujoco.mjtObj.mjOBJ_BODY, base, vel, 0)
        rot = d.xmat[base].reshape(3, 3)
        v = rot.T @ vel[3:]  # in the robot's frame
        coeff = np.array([self.properties.DragCoeffX, self.properties.DragCoeffY, self.properties.DragCoeffZ])
        drag = -np.sign(v) * v * v * coeff
        self.robot.apply_wrench(self.name, rot @ drag, np.zeros(3))


COMPONENT = Drag
