"""MORSE's BarePR2: the PR2's body alone, without armatures, sensors or actuators."""

from typing import ClassVar

from morsec.component.catalogue import component_class

BasePR2 = component_class("robots", "pr2")


class BarePR2(BasePR2):
    """Willow Garage's PR2 without any sensor or actuator, MORSE's BarePR2: the body of `pr2` (BasePR2) alone,
    its omnidirectional base (0.65 m square) and tower, one rigid body of 136 kg, its origin on the floor.
    Its torso lift, head and arms are not there (they are BasePR2's armatures); append components to it as to
    any robot."""

    short_descr = "Willow Garage PR2, the body alone (no armatures, sensors or actuators)"
    builder_name = "BarePR2"
    default_components = ()
    component_mounts: ClassVar[dict[str, tuple[str, str]]] = {}
    builder_interface: ClassVar[dict[str, dict[str, tuple]]] = {}


COMPONENT = BarePR2
