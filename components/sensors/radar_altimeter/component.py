import mujoco
import numpy as np
from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor

DOWN = np.array([0.0, 0.0, -1.0])
# geom groups a ray sees: not 2 (visual geoms, component fragments) nor 5 (sites)
GROUPS = np.array([1, 1, 0, 1, 1, 0], dtype=np.uint8)
MAX_PASSES = 32  # geoms of the robot itself (or non-colliding ones) the ray may pass through
STEP_M = 1e-6


class RadarAltimeter(Sensor):
    """Height above what is below: the distance from the sensor straight down (world -z) to the first
    collision geometry that is not part of the sensor's own robot (ground, objects, other robots),
    found with `mujoco.mj_ray`; +inf when nothing is within `MaxRange`."""

    short_descr = "Distance to the ground (or obstacle) straight below"
    builder_name = "RadarAltimeter"
    frequency = 60.0

    class Properties(ComponentProperties):
        MaxRange: float = Field(30.0, gt=0.0, description="farthest detected distance, m; beyond it z is +inf")

    data = (
        DataField("z", 0.0, "float", "distance to the first obstacle straight below the sensor, m; "
                  "inf when none within MaxRange"),
    )

    def start(self):
        self.own_root = int(self.sim.model.body_rootid[self.body_id])
        self.geom = np.zeros(1, dtype=np.int32)

    def default_action(self):
        self.local_data["z"] = self.cast(self.position().copy(), DOWN, self.properties.MaxRange)

    def cast(self, start, direction, max_range: float) -> float:
        m, d = self.sim.model, self.sim.data
        travelled = 0.0
        for _ in range(MAX_PASSES):
            dist = mujoco.mj_ray(m, d, start, direction, GROUPS, 1, -1, self.geom)
            if dist < 0 or travelled + dist > max_range:
                return float("inf")
            g = int(self.geom[0])
            if m.body_rootid[m.geom_bodyid[g]] != self.own_root and (m.geom_contype[g] or m.geom_conaffinity[g]):
                return float(travelled + dist)
            travelled += dist + STEP_M  # the robot's own geometry, or a geom that nothing collides with
            start = start + direction * (dist + STEP_M)
        return float("inf")


COMPONENT = RadarAltimeter
