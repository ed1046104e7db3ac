from typing import ClassVar

from pydantic import Field

from morsec.component import Robot, WheeledRobotProperties


class Pioneer3DX(Robot):
    """MobileRobots Pioneer 3-DX: a 9 kg differential-drive indoor robot, 0.445 x 0.38 x 0.24 m, two
    0.195 m drive wheels 0.33 m apart and a passive rear caster. Its origin is in the middle of the body,
    0.15 m above the ground as MORSE's (0.0525 m above the drive axle). The wheel joints are `wheel_left_joint` and
    `wheel_right_joint` (axis y), the wheel links are named by `WheelFLName` / `WheelFRName`."""

    short_descr = "Differential-drive indoor robot with a rear caster"
    builder_name = "Pioneer3DX"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.15
    # what motion_vw_diff reads (see its README)
    wheel_radius: ClassVar[float] = 0.0975
    wheel_track: ClassVar[float] = 0.33
    left_wheel_joints: ClassVar[tuple[str, ...]] = ("wheel_left_joint",)
    right_wheel_joints: ClassVar[tuple[str, ...]] = ("wheel_right_joint",)
    wheel_kv: ClassVar[float] = 10.0
    wheel_max_torque: ClassVar[float] = 10.0

    class Properties(WheeledRobotProperties):
        GroundRobot: bool = True
        WheelFLName: str = Field("Wheel_L", description="link name of the left drive wheel")
        WheelFRName: str = Field("Wheel_R", description="link name of the right drive wheel")
        CasterWheelName: str = Field("CasterWheel", description="link name of the rear caster wheel")


COMPONENT = Pioneer3DX
