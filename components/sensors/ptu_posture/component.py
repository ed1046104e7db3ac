"""MORSE's PTUPosture: the pan and tilt angles of a pan-tilt unit, read from its joints."""

from __future__ import annotations

import mujoco

from morsec.component import DataField, Sensor


class PTUPosture(Sensor):
    """The current pan and tilt of a pan-tilt unit (`ptu`), rad. Append it to the unit (it then rides on
    the tilt body); if it is not on a unit, it reads the first unit of its robot."""

    short_descr = "Pan and tilt angles of a pan-tilt unit"
    builder_name = "PTUPosture"
    frequency = 60.0

    data = (
        DataField("pan", 0.0, "float", "pan angle, rad, about the unit's z axis (positive: to the left)"),
        DataField("tilt", 0.0, "float", "tilt angle, rad, about the pan body's y axis (positive: down)"),
    )

    def start(self):
        m = self.sim.model
        candidates = []
        parent = self.sim.by_name[self.name].parent
        while parent in self.sim.by_name:  # the unit it is appended to, or one above it
            candidates.append(parent)
            parent = self.sim.by_name[parent].parent
        robot = self.sim.by_name[self.name].robot
        candidates += [c.fqn for c in self.sim.components_of(robot) if c.fqn not in candidates]
        for fqn in candidates:
            pan = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, f"{fqn}/pan")
            tilt = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, f"{fqn}/tilt")
            if pan >= 0 and tilt >= 0:
                self.unit = fqn
                self._adr = (int(m.jnt_qposadr[pan]), int(m.jnt_qposadr[tilt]))
                return
        raise ValueError("no pan-tilt unit to read: append the sensor to a ptu")

    def default_action(self):
        q = self.sim.data.qpos
        self.local_data["pan"] = float(q[self._adr[0]])
        self.local_data["tilt"] = float(q[self._adr[1]])


COMPONENT = PTUPosture
