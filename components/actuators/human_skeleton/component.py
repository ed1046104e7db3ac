"""MORSE's human skeleton: the armature of the `human` avatar (its `skeleton`), posed by five IK targets solved
together, as Blender's IK tree, and walking when the human moves."""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from morsec.component.catalogue import component_class
from morsec.kits.ik import WholeBodyIK

Armature = component_class("actuators", "armature")

# Each joint's stiffness in the inverse kinematics: how much it resists taking a share of a movement (Blender's
# IK stiffness; 1 is neutral), by bone or group of bones, and axis. MORSE's human_rig.blend is not readable
# here: these are fitted so that MORSE's own human_ik test reads the joint values it recorded (within a
# quarter of its tolerance). What they make the body do: the spine bends sideways readily and twists
# reluctantly; the head turns mostly in neck03 and the head; the upper arm bends at upperarm02.
STIFFNESS: dict[str, float] = {
    "spine:x": 3.5, "spine:y": 4.6, "spine:z": 0.075, "root": 5.8,
    "neck:x": 0.87, "neck:z": 18.0, "neck01:y": 1.5, "neck02:y": 13.0, "neck03:y": 0.22, "head:y": 0.47,
    "clavicle": 0.73, "shoulder01": 3.8, "upperarm01:x": 12.0, "upperarm01:y": 2.2, "upperarm01:z": 430.0,
    "upperarm02:x": 0.2, "upperarm02:y": 2.0, "upperarm02:z": 2.3, "lowerarm": 4.8, "wrist": 1.4, "leg": 3.5,
}
GROUPS = (("spine", ("root", "spine")), ("neck", ("neck", "head")),
          ("arm", ("clavicle", "shoulder", "upperarm", "lowerarm", "wrist")),
          ("leg", ("pelvis", "upperleg", "lowerleg", "foot")))
IK_ROT_WEIGHT = 3.0  # m per rad: a target's orientation weighs this much against its position

# the walk cycle (MORSE played human_rig.blend's "walk" action while the human moved): one stride (two steps)
# per STRIDE m, swings about each bone's first axis, rad, {joint: (amplitude, phase in cycles)}
STRIDE = 1.3
WALK = {
    "upperleg01_L": (-0.35, 0.0), "upperleg01_R": (-0.35, 0.5),
    "lowerleg01_L": (0.45, 0.15), "lowerleg01_R": (0.45, 0.65),
    "upperarm01_L": (0.25, 0.5), "upperarm01_R": (0.25, 0.0),
    "lowerarm01_L": (0.15, 0.6), "lowerarm01_R": (0.15, 0.1),
}
WALK_BLEND_S = 0.25  # s to take up or leave the walk
TURN_STRIDE = math.pi  # rad of turning on the spot per stride


def stiffness_of(joint: str, axis: str) -> float:
    """The stiffness of joint `<bone>` or `<bone>:<axis>` turning about `axis` (x, y or z of the bone), looked up
    by bone, bone without its side (_L, _R), then its group, each with and without the axis."""
    bone = joint.partition(":")[0]
    base = bone[:-2] if bone[-2:] in ("_L", "_R") else bone
    group = next((g for g, prefixes in GROUPS if base.startswith(prefixes)), base)
    for key in (f"{bone}:{axis}", bone, f"{base}:{axis}", base, f"{group}:{axis}", group):
        if key in STIFFNESS:
            return STIFFNESS[key]
    return 1.0


class HumanSkeleton(Armature):
    """The human avatar's armature (`human.skeleton`), MORSE's `HumanSkeleton`: MakeHuman's bones (root,
    spine05 .. spine01, neck01 .. neck03, head, clavicle, shoulder01, upperarm01/02, lowerarm01/02, wrist,
    pelvis, upperleg01/02, lowerleg01/02, foot, each side _L / _R). A bone is a joint about its first free axis,
    named as the bone (what `joint_states` reads), and `<bone>:y`, `<bone>:z` for its other axes. Five IK
    targets, at the tails of head, wrist_L, wrist_R, foot_L and foot_R, are solved together from the rest
    pose, as Blender's IK tree: a hand that reaches bends the spine, and the other targets stay where they
    are. While the human moves, the legs and arms swing in a walk cycle."""

    short_descr = "The human avatar's skeleton: MakeHuman bones, five IK targets, walk cycle"
    builder_name = "HumanSkeleton"
    xacro = "human_skeleton.urdf.xacro"
    mount_body = "head:z"
    ik_targets = {bone: f"{bone}_tail" for bone in ("head", "wrist_L", "wrist_R", "foot_L", "foot_R")}
    joint_armature: ClassVar[dict[str, float]] = {"*": 0.02}

    def start(self):
        super().start()
        axes = ["xyz"[int(np.argmax(np.abs(self.sim.model.jnt_axis[j])))] for j in self.servos.joints]
        self._whole = WholeBodyIK(self.sim.model, self.servos,
                                  [stiffness_of(n, a) for n, a in zip(self.names, axes)], IK_ROT_WEIGHT)
        self._walk_phase = 0.0
        self._walk_weight = 0.0
        self._last_pose = self.robot.pose()
        self._walk = [(self.servos.index[j], a, p) for j, (a, p) in WALK.items() if j in self.servos.index]

    def _orientation_counts(self) -> bool:
        return True

    def _solve_target(self, target: str, pos, rot, **kwargs):
        """Every target at once, `target` at (pos, rot), the others where they are (MORSE's empties), from the
        rest pose; returns what the armature's single-target solver returns, for `target`."""
        goals, order = [], []
        for name, body in self._ik_bodies.items():
            goal = (pos, rot) if name == target else self._to_world(*self._ik_poses[name])
            goals.append((body, *goal))
            order.append(name)
        q, errors = self._whole.solve(self.sim.data, goals)
        dist, angle = errors[order.index(target)]
        return q, dist, angle

    # ---- walking: MORSE's human played its walk action while an actuator moved it
    def default_action(self):
        super().default_action()
        pos, rot = self.robot.pose()
        last_pos, last_rot = self._last_pose
        self._last_pose = (pos, rot)
        step = float(np.linalg.norm((pos - last_pos)[:2]))
        turn = abs(math.atan2(rot[1, 0], rot[0, 0]) - math.atan2(last_rot[1, 0], last_rot[0, 0]))
        turn = min(turn, 2 * math.pi - turn)
        moving = step > 1e-4 or turn > 1e-4
        dt = 1.0 / self.frequency
        self._walk_weight = min(1.0, self._walk_weight + dt / WALK_BLEND_S) if moving else \
            max(0.0, self._walk_weight - dt / WALK_BLEND_S)
        self._walk_phase = (self._walk_phase + step / STRIDE + turn / TURN_STRIDE) % 1.0
        if self._walk_weight <= 0.0:
            return
        # the swing is added to what the servos are told, not to the posture they keep (servos.setpoint)
        servos = self.servos
        servos.release()  # the posture is held at rest (Armature); the swing moves the joints off it
        posture = servos.setpoint.copy()
        swing = posture.copy()
        for i, amplitude, phase in self._walk:
            swing[i] += self._walk_weight * amplitude * math.sin(2 * math.pi * (self._walk_phase + phase))
        servos.command(swing)
        servos.setpoint = posture


COMPONENT = HumanSkeleton
