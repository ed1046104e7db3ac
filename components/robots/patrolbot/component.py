from typing import ClassVar

from pydantic import Field

from morsec.component import Robot, WheeledRobotProperties


class PatrolBot(Robot):
    """Adept MobileRobots PatrolBot: a 46 kg differential-drive indoor patrol robot, 0.59 x 0.48 x 0.38 m, two
    0.19 m drive wheels 0.40 m apart and a passive rear caster. Its origin is 0.10 m above the ground (5 mm
    above the drive axle). Drive it with `motion_vw_diff` (through its wheels, joints `wheel_left_joint` and
    `wheel_right_joint`) or `motion_vw`; the wheel links are named by `WheelFLName` / `WheelFRName`."""

    short_descr = "Differential-drive indoor patrol robot with a rear caster"
    builder_name = "PatrolBot"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.10
    # what motion_vw_diff reads (see its README)
    wheel_radius: ClassVar[float] = 0.095
    wheel_track: ClassVar[float] = 0.40
    left_wheel_joints: ClassVar[tuple[str, ...]] = ("wheel_left_joint",)
    right_wheel_joints: ClassVar[tuple[str, ...]] = ("wheel_right_joint",)
    wheel_kv: ClassVar[float] = 20.0
    wheel_max_torque: ClassVar[float] = 60.0

    class Properties(WheeledRobotProperties):
        GroundRobot: bool = True
        WheelFLName: str = Field("Wheel_L", description="link name of the left drive wheel")
        WheelFRName: str = Field("Wheel_R", description="link name of the right drive wheel")
        CasterWheelName: str = Field("CasterWheel", description="link name of the rear caster wheel")


COMPONENT = PatrolBot
