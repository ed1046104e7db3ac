import math
from typing import ClassVar

from pydantic import Field

from morsec.component import Robot, RobotProperties

SUSPENSION_STIFFNESS = 15.0  # MORSE's hummer.py, per unit of chassis mass (Bullet's raycast vehicle)
REST_LENGTH = 0.3
WHEEL_RADIUS = 0.5
ATTACH_Z = -0.5


class Hummer(Robot):
    """MORSE's Hummer: a 10 kg car run by Blender's vehicle wrapper (Bullet's raycast vehicle), four wheels on
    a ray-cast suspension, the front pair steered, driven with `steer_force`. Its frame is MORSE's Hummer's:
    y forward, x to the right, z up, its origin the chassis' centre of mass, 1.14 m above the ground; as in
    MORSE's .blend, the car is turned -90 degrees about z, so that it faces +x where a scene puts it with no
    rotation (its yaw then reads -pi/2)."""

    short_descr = "Car on a ray-cast suspension, driven by steer_force"
    builder_name = "Hummer"
    xacro = "robot.urdf.xacro"
    # the suspension's springs carry the car (9.81 m/s^2 over 4 x 15 /s^2 of compression) under its origin
    spawn_height = -ATTACH_Z + (REST_LENGTH - 9.81 / (4 * SUSPENSION_STIFFNESS)) + WHEEL_RADIUS
    # MORSE's hummer.blend turns the car's object -90 degrees about z (the vehicle's forward axis is its y)
    origin_rotation: ClassVar[tuple[float, float, float]] = (0.0, 0.0, -math.pi / 2)
    # Blender's damping and rotation damping of the chassis (fitted to MORSE's steer_force test: MORSE's
    # .blend is not readable here)
    damping: ClassVar[tuple[float, float]] = (0.42, 0.1)

    # what steer_force reads: MORSE's hummer.py's vehicle, wheels in its order (wheel1 .. wheel4) as
    # (spin joint, steering joint or None, suspension hard point in the robot frame), Bullet's tuning
    vehicle_wheels: ClassVar[tuple[tuple[str, str | None, tuple[float, float, float]], ...]] = (
        ("wheel_front_right_joint", "steer_right_joint", (1.3, 1.6, ATTACH_Z)),
        ("wheel_front_left_joint", "steer_left_joint", (-1.3, 1.6, ATTACH_Z)),
        ("wheel_rear_right_joint", None, (1.3, -2.3, ATTACH_Z)),
        ("wheel_rear_left_joint", None, (-1.3, -2.3, ATTACH_Z)),
    )
    wheel_radius: ClassVar[float] = WHEEL_RADIUS
    suspension_rest_length: ClassVar[float] = REST_LENGTH
    suspension_stiffness: ClassVar[float] = SUSPENSION_STIFFNESS
    suspension_damping: ClassVar[float] = 10.0  # Bullet's relaxation damping (setSuspensionDamping)
    suspension_compression: ClassVar[float] = 2.0  # Bullet's compression damping (setSuspensionCompression)
    roll_influence: ClassVar[float] = 0.05

    class Properties(RobotProperties):
        GroundRobot: bool = True
        brakes: float = Field(0.0, description="MORSE vehicle wrapper: brake value (recorded; steer_force "
                              "brakes)")
        friction: float = Field(200.0, description="MORSE vehicle wrapper: the tyres' friction slip (Bullet's "
                                "setTyreFriction): a wheel's grip is at most this times the load it carries")
        force: float = Field(0.0, description="MORSE vehicle wrapper: engine force (recorded; steer_force "
                             "drives)")
        steer: float = Field(0.0, description="MORSE vehicle wrapper: steering value (recorded; steer_force "
                             "steers)")
        init: int = Field(0, description="MORSE vehicle wrapper: initialised flag (recorded)")
        cid: int = Field(0, description="MORSE vehicle wrapper: Bullet constraint id (recorded)")


COMPONENT = Hummer
