from typing import ClassVar

from pydantic import Field

from morsec.component import Robot, RobotProperties


class Hummer(Robot):
    """A HMMWV-like 4x4 car, 4.60 x 2.16 x 1.85 m, 2440 kg: steered front wheels, four driven wheels
    (track 1.82 m, wheelbase 3.30 m, wheel radius 0.47 m), no suspension. Drive it with `steer_force`
    (steering angle, engine force, brake), as MORSE's vehicle-wrapper Hummer. Its origin is at the centre
    of the axles, one wheel radius (0.47 m) above the ground."""

    short_descr = "Car with steered front wheels, driven by steer_force"
    builder_name = "Hummer"
    xacro = "robot.urdf.xacro"
    spawn_height = 0.47

    # what steer_force reads: URDF joint names of the steering hinges (front left, front right) and of
    # the driven wheels in MORSE's vehicle order (front left, front right, rear left, rear right), the
    # wheel radius (m) and the steering servo's gains (N m/rad, N m s/rad)
    steering_joints: ClassVar[tuple[str, ...]] = ("steer_left_joint", "steer_right_joint")
    drive_wheel_joints: ClassVar[tuple[str, ...]] = (
        "wheel_front_left_joint", "wheel_front_right_joint", "wheel_rear_left_joint", "wheel_rear_right_joint")
    wheel_radius: ClassVar[float] = 0.47
    steering_kp: ClassVar[float] = 20000.0
    steering_kv: ClassVar[float] = 800.0

    class Properties(RobotProperties):
        GroundRobot: bool = True
        brakes: float = Field(0.0, description="MORSE vehicle wrapper: brake value (recorded; steer_force "
                              "brakes)")
        friction: float = Field(200.0, description="MORSE vehicle wrapper: Bullet tyre friction (recorded; "
                                "the robot's `friction` sets the MuJoCo one)")
        force: float = Field(0.0, description="MORSE vehicle wrapper: engine force (recorded; steer_force "
                             "drives)")
        steer: float = Field(0.0, description="MORSE vehicle wrapper: steering value (recorded; steer_force "
                             "steers)")
        init: int = Field(0, description="MORSE vehicle wrapper: initialised flag (recorded)")
        cid: int = Field(0, description="MORSE vehicle wrapper: Bullet constraint id (recorded)")


COMPONENT = Hummer
