"""MORSE's PA10: the Mitsubishi PA-10 arm, an armature with six revolute joints seg0 .. seg5."""

from __future__ import annotations

import math

from pydantic import Field

from morsec.component import ComponentProperties, service
from morsec.component.catalogue import component_class

Armature = component_class("actuators", "armature")


class PA10(Armature):
    """The Mitsubishi PA-10 (PA10-6C) arm, MORSE's PA10: six revolute joints seg0 .. seg5 turning about z, y, y,
    z, y, z (base, shoulder, elbow, forearm, wrist, flange), straight up at zero, its tip 1.317 m above its base.
    Stream the six target angles {seg0: .., seg5: ..} (rad) or call `set_rotation_array`: each joint turns to
    its target at `Speed`; every armature service works too. Appended components ride on the flange."""

    short_descr = "Mitsubishi PA-10 arm: six revolute joints seg0 .. seg5 (armature)"
    builder_name = "PA10"
    xacro = "pa10.urdf.xacro"
    mount_body = "seg5"
    ik_targets: dict[str, str] = {}
    joint_armature = {f"seg{i}": 0.1 for i in range(6)}

    class Properties(ComponentProperties):
        Speed: float = Field(1.0, gt=0, description="rotation speed of the joints, rad/s")
        Tolerance: float = Field(math.radians(5.0), gt=0, description="a joint within this angle of its target "
                                 "is there (MORSE's 5 degrees), rad")
        DistanceTolerance: float = Field(0.005, gt=0, description="tolerance when placing an IK target, m")
        LinearSpeed: float = Field(0.05, gt=0, description="speed of prismatic joints, m/s (the PA-10 has none)")
        IKRotationSpeed: float = Field(0.5, gt=0, description="rotation speed of an IK target, rad/s")
        IKLinearSpeed: float = Field(0.5, gt=0, description="linear speed of an IK target, m/s")

        # the names the armature reads
        @property
        def RotationSpeed(self) -> float:  # noqa: N802 (MORSE's property names)
            return self.Speed

        @property
        def AngleTolerance(self) -> float:  # noqa: N802
            return self.Tolerance

    @service
    def set_rotation_array(self, seg0: float = 0.0, seg1: float = 0.0, seg2: float = 0.0, seg3: float = 0.0,
                           seg4: float = 0.0, seg5: float = 0.0) -> None:
        """Set the six joints' targets (rad, base to flange): they turn there at `Speed` (MORSE's service)."""
        self._stop_motions()
        self.joint_speed.clear()
        for i, value in enumerate((seg0, seg1, seg2, seg3, seg4, seg5)):
            self.local_data[f"seg{i}"] = float(value)


COMPONENT = PA10
