"""Component properties (MORSE's add_property): the base model, and the properties several components share,
each declared once with its description.

A component inherits a shared property from one of these bases; to give it another default it redeclares
the name with the new default only, and keeps the base's description and bounds:

    class Properties(RobotProperties):
        GroundRobot: bool = True
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field


class ComponentProperties(BaseModel):
    """Base of every component's properties: basic types only (bool, int, float, str), unknown names rejected.
    Every property has a description (`Field(default, description=...)`); one redeclared without a
    description (to change its default) keeps the description, and unless it gives its own the bounds
    (ge, gt, ...), of the class it comes from."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, validate_assignment=True, defer_build=True)

    @classmethod
    def __pydantic_init_subclass__(cls, **kwargs) -> None:
        super().__pydantic_init_subclass__(**kwargs)
        inherited = False
        for name, info in cls.model_fields.items():
            if info.description:
                continue
            for base in cls.__mro__[1:]:
                declared = getattr(base, "__pydantic_fields__", {}).get(name)
                if declared is not None and declared.description:
                    info.description = declared.description
                    if not info.metadata and info.annotation == declared.annotation:
                        info.metadata = list(declared.metadata)
                    inherited = True
                    break
        if inherited:  # validation, the JSON Schema and the docs read them from the rebuilt model
            cls.model_rebuild(force=True)


class RobotProperties(ComponentProperties):
    """What every robot has."""

    NoGravity: bool = Field(False, description="float: gravity is compensated on every body of the robot "
                            "(MuJoCo's gravcomp); false: it falls")
    GroundRobot: bool = Field(False, description="velocity actuators leave the vertical velocity, roll and pitch "
                              "to physics, so the robot stays on the ground; false: they set its whole body "
                              "velocity (MORSE's GroundRobot)")


class WheeledRobotProperties(RobotProperties):
    """MORSE's WheeledRobot / PhysicsDifferentialRobot settings, for robots modelled on them."""

    HasSuspension: bool = Field(False, description="MORSE PhysicsWheelRobot: wheels on suspensions (recorded; the "
                                "wheels are rigid here)")
    Influence: float = Field(0.1, description="MORSE wheel suspension influence (recorded)")
    Friction: float = Field(0.8, description="MORSE wheel friction (recorded; the robot's `friction` sets MuJoCo's)")
    WheelFLName: str = Field("", description="link name of the front left wheel")
    WheelFRName: str = Field("", description="link name of the front right wheel")
    FixTurningSpeed: float = Field(0.0, description="MORSE PhysicsDifferentialRobot: the wheel track used to compute "
                                   "the wheel speeds from (v, w), m, compensating for slip (0: the real track)")


class ControlTypeProperties(ComponentProperties):
    """Actuators that move their robot through MORSE's robot.apply_speed."""

    ControlType: Literal["Velocity", "Position"] = Field(
        "Velocity", description="Velocity: the command sets the robot's body velocity every tick (velocity servos "
        "on its base; gravity and contacts still act); Position: the robot is displaced by speed / frequency and "
        "turned by rate / frequency each tick, kinematically")


class ComputationModeProperties(ComponentProperties):
    """Sensors measuring velocities or accelerations, from the physics or from the pose."""

    ComputationMode: Literal["Automatic", "Velocity", "Position"] = Field(
        "Automatic", description="Velocity: from the physics (MuJoCo's velocity of the sensor's frame); Position: "
        "finite differences of the sensor's pose between ticks (for robots moved kinematically); Automatic: "
        "Velocity on a robot with a free body, Position on a fixed one (fake_robot, static robots)")


class RotorcraftProperties(ComponentProperties):
    """The attitude loop of MORSE's rotorcraft controllers."""

    RollPitchPgain: float = Field(9.7, description="proportional gain of the roll and pitch control, 1/s^2")
    RollPitchDgain: float = Field(2.0, description="derivative gain of the roll and pitch control, 1/s")
    YawPgain: float = Field(12.0, description="proportional gain of the yaw control, 1/s^2")
    YawDgain: float = Field(6.0, description="derivative gain of the yaw control, 1/s")


class GeomagneticDateProperties(ComponentProperties):
    """Sensors of the Earth's magnetic field (magnetometer, IMU): the date the World Magnetic Model is taken at."""

    date: float = Field(0.0, ge=0.0, description="date of the magnetic field as a decimal year (2025.5 is early "
                        "July 2025); 0: the day the simulation starts")
