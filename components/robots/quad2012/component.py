from morsec.component import RobotProperties
from morsec.component.catalogue import component_class

Quadrotor = component_class("robots", "quadrotor")


class QUAD2012(Quadrotor):
    """MORSE's QUAD2012: the quadrotor flown by a `stabilized_quadrotor` actuator, which moves it
    kinematically (MORSE's model has no rigid-body physics). Same body as `quadrotor` (1.0 kg, '+' layout,
    0.56 m tip to tip); it floats (NoGravity): it stays where `translate` puts it until an actuator moves it,
    and its origin is where `translate` puts it (z = 0: on the ground plane, as MORSE's)."""

    short_descr = "Quadrotor for the stabilised (kinematic) flight model"
    builder_name = "QUAD2012"
    xacro = "../quadrotor/robot.urdf.xacro"
    damping = (0.0, 0.0)  # no rigid body in MORSE's Bullet: nothing damps it

    class Properties(RobotProperties):
        NoGravity: bool = True


COMPONENT = QUAD2012
