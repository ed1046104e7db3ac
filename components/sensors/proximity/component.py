import numpy as np
from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor, service


class Proximity(Sensor):
    """Which tracked objects are near the robot: every robot, object or component carrying the property
    named `Track` (every robot has `Robot_Tag`; a robot's or component's other game properties are its
    `tags`), other than the sensor's own robot and its components, whose origin is within `Range` of the
    robot's origin, with its distance."""

    short_descr = "Names and distances of tracked objects within range"
    builder_name = "Proximity"
    frequency = 12.0

    class Properties(ComponentProperties):
        Range: float = Field(30.0, ge=0.0, description="detection radius around the robot's origin, m (MORSE's "
                             "builder default; its core default is 100)")
        Track: str = Field("Robot_Tag", description="property the detected objects carry (or their Type)")

    data = (
        DataField("near_objects", {}, "dict[str, float]", "tracked objects within range: {name: distance from the "
                  "robot's origin, m}"),
        DataField("near_robots", {}, "dict[str, float]", "deprecated alias of near_objects"),
    )

    def default_action(self):
        p = self.properties
        xpos = self.sim.data.xpos
        origin = xpos[self.robot.body_id]
        roots = self.sim.model.body_rootid
        near = {}
        for obj in self.sim.objects_with(p.Track):
            if roots[obj.body_id] == self.robot.body_id:  # its own robot, or a tagged component on it
                continue
            distance = float(np.linalg.norm(xpos[obj.body_id] - origin))
            if distance <= p.Range:
                near[obj.name] = distance
        self.local_data["near_objects"] = near
        self.local_data["near_robots"] = near

    @service
    def set_range(self, range: float) -> None:
        """Detection radius, m."""
        self.properties.Range = float(range)

    @service
    def set_tracked_tag(self, tag: str) -> None:
        """Name of the property the detected objects carry."""
        self.properties.Track = str(tag)


COMPONENT = Proximity
