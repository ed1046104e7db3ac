from typing import ClassVar

from pydantic import Field

from morsec.component import Robot, RobotProperties


class SegwayRMP400(Robot):
    """Segway RMP 400: a 4-wheel skid-steer outdoor platform, 1.09 x 0.76 m, 118 kg, four 0.533 m wheels
    (track 0.62 m, wheelbase 0.556 m), the two wheels of each side driven at the same speed by
    `motion_vw_diff` (MORSE's PhysicsDifferentialRobot). Its origin is at the centre of the axles, one
    wheel radius (0.2667 m) above the ground."""

    short_descr = "4-wheel skid-steer platform driven through its wheels"
    builder_name = "SegwayRMP400"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.2667

    # what motion_vw_diff reads (MORSE's PhysicsDifferentialRobot): URDF joint names of the driven
    # wheels of each side, wheel radius and distance between the left and right wheel centres
    wheel_radius: ClassVar[float] = 0.2667
    wheel_track: ClassVar[float] = 0.62
    left_wheel_joints: ClassVar[tuple[str, ...]] = ("wheel_left_joint", "wheel_rear_left_joint")
    right_wheel_joints: ClassVar[tuple[str, ...]] = ("wheel_right_joint", "wheel_rear_right_joint")
    wheel_kv: ClassVar[float] = 3000.0  # wheel velocity servo gain, N m per rad/s
    wheel_max_torque: ClassVar[float] = 300.0  # N m per wheel
    # drive train (hub motor rotor through the gearbox) reflected on each wheel joint, kg m^2: it also
    # balances MuJoCo's contact solver between the light wheel spin and the heavy chassis, so that
    # skid-steer turning slips as Coulomb friction says (without it the robot turns at half the rate)
    joint_armature: ClassVar[dict[str, float]] = {
        j: 2.0 for j in ("wheel_left_joint", "wheel_rear_left_joint", "wheel_right_joint", "wheel_rear_right_joint")}

    class Properties(RobotProperties):
        GroundRobot: bool = Field(True, description="keeps physics-driven vertical velocity, roll and pitch "
                                  "under velocity actuators")
        HasSuspension: bool = Field(False, description="MORSE PhysicsWheelRobot: wheels on suspensions "
                                    "(recorded; the wheels are rigid here)")
        HasSteering: bool = Field(False, description="MORSE PhysicsWheelRobot: wheels steer (recorded; they "
                                  "do not)")
        Influence: float = Field(0.1, description="MORSE wheel suspension influence (recorded)")
        Friction: float = Field(0.8, description="MORSE wheel friction (recorded)")
        WheelFLName: str = Field("wheel1", description="link name of the front left wheel")
        WheelFRName: str = Field("wheel2", description="link name of the front right wheel")
        WheelRLName: str = Field("wheel3", description="link name of the rear left wheel")
        WheelRRName: str = Field("wheel4", description="link name of the rear right wheel")
        FixTurningSpeed: float = Field(1.5, description="MORSE PhysicsDifferentialRobot: replaces the wheel "
                                       "track in the wheel-speed formula (0: the real track). 1.5 makes this "
                                       "skid-steered robot turn at the commanded w on MuJoCo (its wheels slip "
                                       "sideways when turning); MORSE's 1.16 was tuned for Bullet")


COMPONENT = SegwayRMP400
