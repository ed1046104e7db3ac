"""MORSE's ArmaturePose: the joint state of the armature it is appended to, {joint: value}."""

from __future__ import annotations

import mujoco
import numpy as np

from morsec.component import DataField, Sensor, service
from morsec.kits.servos import is_bone


class ArmaturePose(Sensor):
    """Streams the joint state of its armature (an `armature`, `kuka_lwr` ...): {joint name: value}, rad for
    revolute joints and m for prismatic ones, root to tip after `timestamp`. A bone that turns about several
    axes (the human's) is one entry, its joint about its first axis (MORSE's value of a bone). Append it to
    the armature (it then rides on the arm's end); if it is not on one, it reads the first armature of its
    robot."""

    short_descr = "Joint state of an armature (arm)"
    builder_name = "ArmaturePose"
    frequency = 60.0

    data = ()  # the armature's joints: {joint name: position}, root to tip
    extra_field = DataField("<joint>", 0.0, "float", "position of each joint of the armature (e.g. kuka_1 ... "
                            "kuka_7), root to tip: rad (revolute) or m (prismatic)")

    def start(self):
        m = self.sim.model
        runtime = self.sim.by_name[self.name]
        candidates = []
        parent = runtime.parent
        while parent in self.sim.by_name:
            candidates.append(parent)
            parent = self.sim.by_name[parent].parent
        candidates += [c.fqn for c in self.sim.components_of(runtime.robot) if c.fqn not in candidates]
        hinge_slide = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
        for fqn in candidates:
            prefix = fqn + "/"
            named = ((j, mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) or "") for j in range(m.njnt))
            ids = [j for j, name in named if int(m.jnt_type[j]) in hinge_slide and name.startswith(prefix)
                   and is_bone(name[len(prefix):])]
            if ids:
                self.armature = fqn
                self.joints = np.array(ids, dtype=int)
                self.names = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j)[len(prefix):] for j in ids]
                self._adr = m.jnt_qposadr[self.joints].astype(int)
                break
        else:
            raise ValueError("no armature to read: append the sensor to an armature (e.g. kuka_lwr)")
        self.default_action()

    def default_action(self):
        q = self.sim.data.qpos[self._adr]
        for name, value in zip(self.names, q):
            self.local_data[name] = float(value)

    @service
    def get_joints(self) -> list[str]:
        """The names of the armature's joints, root to tip."""
        return list(self.names)

    @service
    def get_state(self) -> dict[str, float]:
        """{joint: value} now (rad or m)."""
        q = self.sim.data.qpos[self._adr]
        return {n: float(v) for n, v in zip(self.names, q)}

    @service
    def get_joint(self, joint: str) -> float:
        """The value of one joint now (rad or m)."""
        if joint not in self.names:
            raise ValueError(f"joint <{joint}> does not exist in armature {self.armature} "
                             f"(joints: {', '.join(self.names)})")
        return float(self.sim.data.qpos[self._adr[self.names.index(joint)]])

    @service
    def get_joints_length(self) -> dict[str, float]:
        """{joint: length, m}: the length of the segment each joint moves (MORSE's bone), from it to the next
        joint; the last one, to the end of the arm (a link fixed on the last one, as the KUKA's tip), else 0."""
        m, d = self.sim.model, self.sim.data
        anchors = d.xanchor[self.joints]
        out = {}
        for i, name in enumerate(self.names):
            if i + 1 < len(self.names):
                out[name] = float(np.linalg.norm(anchors[i + 1] - anchors[i]))
                continue
            last = int(m.jnt_bodyid[self.joints[i]])
            ends = [b for b in range(m.nbody) if int(m.body_parentid[b]) == last and int(m.body_jntnum[b]) == 0
                    and (mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_BODY, b) or "").startswith(self.armature + "/")]
            out[name] = float(np.linalg.norm(d.xpos[ends[0]] - anchors[i])) if ends else 0.0
        return out


COMPONENT = ArmaturePose
