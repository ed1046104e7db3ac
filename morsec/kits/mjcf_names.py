"""How morsec names things in the MJCF it writes, spelled once: the compiler and its templates write these
names, the runtime and components look them up.

A robot's (or a device's) bodies, joints and servos are prefixed with its name and '/', which scene names
cannot contain; components are named by their fully-qualified name (robot.arm.camera)."""

from __future__ import annotations

SEPARATOR = "/"
BASE_SERVO_AXES = ("vx", "vy", "wz")  # a robot's base velocity servos: forward, lateral, yaw
# a robot's velocity dampers (Blender's damping): along and about its base frame's x, y, z
DAMPER_AXES = ("x", "y", "z", "rx", "ry", "rz")
DEFAULT_CAMERA = "morsec_default"  # the environment's camera (set_camera_location / set_camera_rotation)
ZONE_PREFIX = "zone"
WORLD_SITE = "morsec_world"  # a site at the world origin: the frame of the locks' dampers (refsite)


def part(owner: str, name: str) -> str:
    """A link body, a joint or a joint's position servo of a robot or device: `robot/arm_link_1`."""
    return f"{owner}{SEPARATOR}{name}"


def base_servo(robot: str, axis: str) -> str:
    """One of a robot's base velocity servos (axis in BASE_SERVO_AXES)."""
    return part(robot, axis)


def damper(robot: str, axis: str) -> str:
    """One of a robot's velocity dampers (axis in DAMPER_AXES)."""
    return part(robot, f"damping_{axis}")


def centre_of_mass(robot: str) -> str:
    """The site at a robot's centre of mass (its links', at rest), where its dampers act."""
    return part(robot, "centre_of_mass")


def lock(owner: str, axis: str) -> str:
    """The damper that holds a robot's or object's lock on `axis` (location_z, rotation_x, ...)."""
    return part(owner, f"lock_{axis}")


def zone_site(zone: str) -> str:
    return part(ZONE_PREFIX, zone)


def owner(name: str) -> str:
    """The robot or device a part belongs to: `robot/arm_link_1` -> `robot`."""
    return name.rsplit(SEPARATOR, 1)[0]


def belongs_to(name: str, owner_name: str) -> bool:
    return name == owner_name or name.startswith(owner_name + SEPARATOR)
