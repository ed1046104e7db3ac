"""MORSE's MocapControl: motion capture driving an armature (a human's skeleton) joint by joint."""

from __future__ import annotations

import logging

from morsec.component import Actuator, ComponentProperties, DataField

log = logging.getLogger("morsec.actuators.mocap_control")


class MocapBuilder:
    """MORSE's builder: MocapControl() takes no name."""

    def __init__(self):
        super().__init__(None)


class MocapControl(Actuator):
    """Motion capture: the joint angles a capture system streams in, {joint: rad}, are put on an armature at
    once, every tick, as MORSE's MocapControl put a Kinect's skeleton on the human (MORSE's builder kept the
    class; its module was gone by 2022). The armature is the one it is appended to, else the first of its
    robot (a human's `skeleton`). Joints left out keep their angles; an unknown joint is reported once."""

    short_descr = "Motion capture: streamed joint angles put on an armature (a human's skeleton)"
    builder_name = "MocapControl"
    frequency = 60.0
    builder_mixin = MocapBuilder

    class Properties(ComponentProperties):
        pass

    data = ()
    extra_field = DataField("<joint>", 0.0, "float", "the angle of a joint of the armature (a human's bone: "
                            "neck03, upperarm01_L ...), rad")

    def start(self) -> None:
        runtime = self.sim.by_name[self.name]
        chain = [runtime.parent] + [c.fqn for c in self.sim.components_of(runtime.robot)]
        # an armature: a component with joint servos and IK targets (armature, kuka_lwr, human_skeleton ...)
        self.armature = next((self.sim.by_name[f].instance for f in chain if f in self.sim.by_name
                              and hasattr(type(self.sim.by_name[f].instance), "ik_targets")), None)
        if self.armature is None:
            raise ValueError("no armature to drive: append it to an armature or to a robot that has one "
                             "(a human)")
        self._warned: set[str] = set()

    def default_action(self) -> None:
        if not self.local_data:
            return
        arm = self.armature
        names, values = [], []
        for joint, value in list(self.local_data.items()):
            if joint in arm.servos.index:
                names.append(arm.servos.index[joint])
                values.append(float(value))
            elif joint not in self._warned:
                self._warned.add(joint)
                log.warning("%s: %s has no joint %r: ignored", self.name, arm.name, joint)
        if names:
            arm._teleport(names, values)


COMPONENT = MocapControl
