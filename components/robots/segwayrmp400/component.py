from typing import ClassVar

from pydantic import Field

from morsec.component import Robot, WheeledRobotProperties


class SegwayRMP400(Robot):
    """Segway RMP 400: a 4-wheel skid-steer outdoor platform, 1.09 x 0.76 m, 118 kg, four 0.533 m wheels
    (track 0.62 m, wheelbase 0.556 m), the two wheels of each side driven at the same speed by
    `motion_vw_diff` (MORSE's PhysicsDifferentialRobot). Its origin is between the wheels, 0.20 m above
    the ground as MORSE's (0.0667 m below the axles)."""

    short_descr = "4-wheel skid-steer platform driven through its wheels"
    builder_name = "SegwayRMP400"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.20

    # what motion_vw_diff reads (MORSE's PhysicsDifferentialRobot): URDF joint names of the driven
    # wheels of each side, wheel radius and distance between the left and right wheel centres
    wheel_radius: ClassVar[float] = 0.2667
    wheel_track: ClassVar[float] = 0.62
    left_wheel_joints: ClassVar[tuple[str, ...]] = ("wheel_left_joint", "wheel_rear_left_joint")
    right_wheel_joints: ClassVar[tuple[str, ...]] = ("wheel_right_joint", "wheel_rear_right_joint")
    # skid steering: wheels that skid sideways in a turn turn the robot at (v_right - v_left) / B, B an
    # effective track wider than the real one. MORSE's Segway on Bullet had B = 1.2 m, as its two test files
    # that turn it recorded: segway_vw (FixTurningSpeed 1.16) turned pi/2 where w added up to 1.61 rad
    # (B = 1.16 * 1.61 / (pi/2) = 1.19 m); rotated_segway, recorded while FixTurningSpeed was 0 (the real
    # 0.624 m track), turned 0.82 rad for 1.61 (B = 0.624 * 1.61 / 0.82 = 1.22 m). motion_vw_diff turns it so.
    morse_skid_track: ClassVar[float] = 1.2
    # the model's own effective track on MuJoCo, which turns the rate into wheel speeds: it turns the robot at
    # 0.97 to 1.04 of the rate asked at 0.25 to 1 m/s (0.83 in place); motion_vw_diff's trim corrects the rest
    skid_track: ClassVar[float] = 1.6
    wheel_kv: ClassVar[float] = 3000.0  # wheel velocity servo gain, N m per rad/s
    wheel_max_torque: ClassVar[float] = 300.0  # N m per wheel
    # drive train (hub motor rotor through the gearbox) reflected on each wheel joint, kg m^2: it also
    # balances MuJoCo's contact solver between the light wheel spin and the heavy chassis, so that
    # skid-steer turning slips as Coulomb friction says (without it the robot turns at half the rate)
    joint_armature: ClassVar[dict[str, float]] = {
        j: 2.0 for j in ("wheel_left_joint", "wheel_rear_left_joint", "wheel_right_joint", "wheel_rear_right_joint")}

    class Properties(WheeledRobotProperties):
        GroundRobot: bool = True
        HasSteering: bool = Field(False, description="MORSE PhysicsWheelRobot: wheels steer (recorded; they "
                                  "do not)")
        WheelFLName: str = "wheel1"
        WheelFRName: str = "wheel2"
        WheelRLName: str = Field("wheel3", description="link name of the rear left wheel")
        WheelRRName: str = Field("wheel4", description="link name of the rear right wheel")
        FixTurningSpeed: float = Field(1.16, description="MORSE PhysicsDifferentialRobot: the wheel track used "
                                       "to compute the wheel speeds from (v, w), m (0: the real track, 0.62 m); "
                                       "the robot turns at w times this over 1.2 m, as MORSE's (1.16: 0.97 w)")


COMPONENT = SegwayRMP400
