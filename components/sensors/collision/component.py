import mujoco
import numpy as np
from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor


class Collision(Sensor):
    """Whether the sensor's robot touches something, and what: MuJoCo's contacts between any geometry of
    the robot and anything else, and, as MORSE's sensor (a small box of its own), what overlaps the 4 cm
    box at the sensor's position (mounted ahead of the robot, it touches an obstacle first).
    The ground plane(s) of the environment are not counted (a ground robot
    always stands on them); other environment geometry (walls, crates) is named after its geom. With
    `only_objects_with_property` only robots and objects carrying that property count.

    As MORSE's (whose Collision ran only while its Blender collision sensor fired), its streams say
    something only while the robot touches something that counts: a client waiting for a message gets
    none before the first contact. `get_local_data` always answers, `collision: false` when free."""

    short_descr = "Contacts of the robot with other objects"
    builder_name = "Collision"
    frequency = 60.0

    class Properties(ComponentProperties):
        only_objects_with_property: str = Field(
            "", description="count only robots and objects carrying this property (or whose Type is it); empty: "
            "everything")

    data = (
        DataField("collision", False, "bool", "true while the robot touches something that counts"),
        DataField("objects", "", "str", "what the robot touches, comma-separated and sorted: robot and object "
                  "names; other environment geometry by its geom name (env/wall_north)"),
    )

    def start(self):
        m = self.sim.model
        self.own_root = int(m.body_rootid[self.body_id])
        self.scene_objects = {obj.body_id: obj for obj in self.sim.objects}
        self.box = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, self.name)
        roots = m.body_rootid[m.geom_bodyid]
        solid = (m.geom_contype != 0) | (m.geom_conaffinity != 0)
        self.others = np.flatnonzero(solid & (roots != self.own_root) & (m.geom_type != mujoco.mjtGeom.mjGEOM_PLANE))
        self.reach = m.geom_rbound[self.others] + float(m.geom_rbound[self.box]) if self.box >= 0 else None

    def default_action(self):
        m, d = self.sim.model, self.sim.data
        wanted = self.properties.only_objects_with_property
        names = set()
        n = d.ncon
        if n:
            contacts = d.contact
            g1, g2 = contacts.geom1[:n], contacts.geom2[:n]
            excluded = getattr(contacts, "exclude", None)
            for i in range(n):
                if excluded is not None and excluded[i]:
                    continue
                a, b = int(g1[i]), int(g2[i])
                ra, rb = m.body_rootid[m.geom_bodyid[a]], m.body_rootid[m.geom_bodyid[b]]
                if ra == self.own_root and rb != self.own_root:
                    other, root = b, int(rb)
                elif rb == self.own_root and ra != self.own_root:
                    other, root = a, int(ra)
                else:
                    continue
                name = self._name(other, root, wanted)
                if name:
                    names.add(name)
        for geom in self._overlapping():
            name = self._name(geom, int(m.body_rootid[m.geom_bodyid[geom]]), wanted)
            if name:
                names.add(name)
        self.local_data["collision"] = bool(names)
        self.local_data["objects"] = ",".join(sorted(names))

    def _overlapping(self) -> list[int]:
        """The other robots' and objects' geoms that overlap the sensor's box."""
        if self.reach is None or not len(self.others):
            return []
        m, d = self.sim.model, self.sim.data
        near = np.linalg.norm(d.geom_xpos[self.others] - d.geom_xpos[self.box], axis=1) <= self.reach
        return [int(g) for g in self.others[near] if mujoco.mj_geomDistance(m, d, self.box, int(g), 1.0, None) <= 0.0]

    def serialize(self) -> dict | None:
        return self.local_data if self.local_data["collision"] else None

    def _name(self, geom: int, root: int, wanted: str) -> str | None:
        obj = self.scene_objects.get(root)
        if obj is not None:
            return obj.name if (not wanted or obj.has(wanted)) else None
        if wanted:
            return None
        m = self.sim.model
        if root == 0:  # environment geometry
            if m.geom_type[geom] == mujoco.mjtGeom.mjGEOM_PLANE:
                return None
            return mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, geom) or "world"
        return mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_BODY, root) or f"body {root}"


COMPONENT = Collision
