from morsec.component import Robot, RobotProperties


class Quadrotor(Robot):
    """A 1.0 kg quadrotor ('+' layout, rotors 0.18 m from the centre, 0.56 m tip to tip), one dynamic
    rigid body as MORSE's `Quadrotor` (quadrotor_dynamic). Fly it with `quadrotor_dynamic_control`
    (rotor speeds -> thrust and torques); with no command it stands on its four legs. Its origin is at
    the centre of the central body, 0.11 m above the floor when it stands."""

    short_descr = "Dynamic quadrotor driven by its rotor speeds"
    builder_name = "Quadrotor"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.11
    lever = 0.18  # distance from the centre to each rotor axis, m (QuadrotorDynamicControl's Lever)

    class Properties(RobotProperties):
        pass


COMPONENT = Quadrotor
