from pydantic import Field

from morsec.component import Robot, RobotProperties


class Pioneer3DX(Robot):
    """MobileRobots Pioneer 3-DX: a 9 kg differential-drive indoor robot, 0.445 x 0.38 x 0.24 m, two
    0.195 m drive wheels 0.33 m apart and a passive rear caster. Its origin is on the drive axle,
    one wheel radius (0.0975 m) above the ground. The wheel joints are `wheel_left_joint` and
    `wheel_right_joint` (axis y), the wheel links are named by `WheelFLName` / `WheelFRName`."""

    short_descr = "Differential-drive indoor robot with a rear caster"
    builder_name = "Pioneer3DX"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.0975

    class Properties(RobotProperties):
        GroundRobot: bool = Field(True, description="keeps physics-driven vertical velocity, roll and pitch "
                                  "under velocity actuators")
        HasSuspension: bool = Field(False, description="MORSE PhysicsWheelRobot: wheels on suspensions")
        Influence: float = Field(0.1, description="MORSE wheel suspension influence")
        Friction: float = Field(0.8, description="MORSE wheel friction")
        WheelFLName: str = Field("Wheel_L", description="link name of the left drive wheel")
        WheelFRName: str = Field("Wheel_R", description="link name of the right drive wheel")
        CasterWheelName: str = Field("CasterWheel", description="link name of the rear caster wheel")
        FixTurningSpeed: float = Field(0.52, description="MORSE PhysicsDifferentialRobot: corrects the "
                                       "turning speed of wheel-driven motion (0: no correction)")


COMPONENT = Pioneer3DX
