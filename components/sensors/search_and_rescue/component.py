"""MORSE's SearchAndRescue sensor: finds victims in a cone in front of the robot, reports them, and heals
the nearest one on request.

MORSE used a Blender radar (a cone along the sensor's +x axis, full aperture `Angle` in degrees, length
`Distance`, hitting objects that have an `Injured` game property). Here an object is in the cone when the
nearest point of one of its geoms' bounding boxes is within `Distance` of the sensor's origin and that point,
or the object's origin, is within Angle / 2 of the +x axis. The victim's state (`Requirements`, `Severity`)
is its property bag in the simulation, shared by every sensor, as MORSE's game properties were.
"""

from __future__ import annotations

import math

import numpy as np
from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor, async_service, service

HEAL_TICKS = 10  # MORSE: the sensor's ticks a healing takes
HEALED_COLOR = (0.5, 1.0, 0.5, 1.0)  # MORSE's colours of a healed and of a partly healed victim
PARTLY_HEALED_COLOR = (0.5, 0.5, 1.0, 1.0)


def _integers(text) -> list[int]:
    """"1,2,3" -> [1, 2, 3] (a list stays a list)."""
    if isinstance(text, (list, tuple)):
        return [int(x) for x in text]
    return [int(x) for x in str(text).split(",") if x.strip()]


class SearchAndRescue(Sensor):
    """Detects the victims (objects with an `Injured` property, such as the `victim` robot) inside a cone
    along the sensor's +x axis, of full aperture `Angle` (degrees) and length `Distance`, and publishes
    their position, requirements and severity. Its services report on the nearest victim in the cone and
    heal it, when it is closer than `Heal_range` and the robot's `Abilities` meet some of its
    requirements: after 10 ticks of the sensor the requirements the robot meets are removed; with none
    left the victim's severity drops to 0 and it turns green."""

    short_descr = "Detects victims in front of the robot and heals them (search and rescue)"
    builder_name = "SearchAndRescue"
    frequency = 6.0

    class Properties(ComponentProperties):
        Heal_range: float = Field(2.0, ge=0.0, description="a victim farther than this (sensor origin to victim "
                                  "origin) cannot be healed, m")
        Abilities: str = Field("1,2", pattern=r"^\s*(\d+\s*(,\s*\d+\s*)*)?$",
                               description="the robot's equipment: comma separated integers, matched against a "
                               "victim's requirements")
        Angle: float = Field(60.0, gt=0.0, le=360.0, description="full aperture of the detection cone around the "
                             "sensor's +x axis, degrees (MORSE's radar angle)")
        Distance: float = Field(10.0, gt=0.0, description="length of the detection cone, m")
        Freq: float = Field(3.0, ge=0.0, description="MORSE's radar pulse setting (recorded; the sensor detects at "
                            "each of its ticks)")

    data = (
        DataField("victim_dict", {}, "dict", "the victims in the cone, by name: {coordinate: {x, y, z} (world "
                  "frame, m), requirements: [int], severity: int}"),
    )

    def start(self):
        self.abilities = _integers(self.properties.Abilities)
        self.victims = [o for o in self.sim.objects if "Injured" in o.properties and o.body_id >= 0]
        for victim in self.victims:  # MORSE's Victim turns its Requirements text into a list at start
            victim.properties["Requirements"] = _integers(victim.properties.get("Requirements", ""))
            victim.properties.setdefault("Severity", 0)
        m = self.sim.model
        self.geoms = {}
        for victim in self.victims:
            bodies = {victim.body_id} | {b for b in range(m.nbody) if _descends(m, b, victim.body_id)}
            self.geoms[victim.name] = [g for g in range(m.ngeom) if int(m.geom_bodyid[g]) in bodies]
        self.nearest = None  # (victim, distance) of the nearest victim in the cone, at the last tick
        self.healing = False
        self.heal_ticks = HEAL_TICKS

    # ------------------------------------------------------------------ detection
    def in_cone(self, victim) -> bool:
        m, d = self.sim.model, self.sim.data
        origin, axis = self.position(), self.rotation()[:, 0]
        half = math.radians(self.properties.Angle) / 2
        for g in self.geoms[victim.name]:
            rot, center, halfsize = d.geom_xmat[g].reshape(3, 3), m.geom_aabb[g, :3], m.geom_aabb[g, 3:]
            local = rot.T @ (origin - d.geom_xpos[g]) - center
            nearest = np.clip(local, -halfsize, halfsize)
            if float(np.linalg.norm(local - nearest)) > self.properties.Distance:
                continue
            point = d.geom_xpos[g] + rot @ (nearest + center)
            if any(_in_cone(p - origin, axis, half) for p in (point, d.xpos[victim.body_id])):
                return True
        return False

    def default_action(self):
        d = self.sim.data
        found = {}
        self.nearest = None
        for victim in self.victims:
            if victim.name == self.robot.name or not self.in_cone(victim):
                continue
            pos = d.xpos[victim.body_id]
            found[victim.name] = {
                "coordinate": {"x": float(pos[0]), "y": float(pos[1]), "z": float(pos[2])},
                "requirements": list(victim.properties["Requirements"]),
                "severity": victim.properties["Severity"],
            }
            distance = float(np.linalg.norm(pos - self.position()))
            if self.nearest is None or distance < self.nearest[1]:
                self.nearest = (victim, distance)
        if self.healing:
            if self.nearest is None:
                self._stop("FAILED", f"No victim within range ({self.properties.Distance:.2f} m)")
            else:
                self._heal(*self.nearest)
                victim = self.nearest[0]
                found[victim.name].update(requirements=list(victim.properties["Requirements"]),
                                          severity=victim.properties["Severity"])
        self.local_data["victim_dict"] = found

    def _heal(self, victim, distance: float) -> None:
        if distance >= self.properties.Heal_range:
            self._stop("FAILED", f"No victim within range ({self.properties.Heal_range:.2f} m)")
            return
        needs = victim.properties["Requirements"]
        if not any(a in needs for a in self.abilities):
            self._stop("FAILED", "Not equipped of helping victim")
            return
        self.heal_ticks -= 1
        if self.heal_ticks > 0:
            return
        needs[:] = [n for n in needs if n not in self.abilities]
        if needs:
            self._paint(victim, PARTLY_HEALED_COLOR)
            self._stop("SUCCESS", f"Victim '{victim.name}' partially healed")
        else:
            victim.properties["Severity"] = 0
            self._paint(victim, HEALED_COLOR)
            self._stop("SUCCESS", f"Victim '{victim.name}' healed")

    def _stop(self, status: str, message: str) -> None:
        self.healing = False
        self.heal_ticks = HEAL_TICKS
        self.completed(status, message)

    def _paint(self, victim, color) -> None:
        rgba = self.sim.model.geom_rgba
        for g in self.geoms[victim.name]:
            if rgba[g, 3] > 0:
                rgba[g] = color

    def interrupt(self):
        self.healing = False
        self.heal_ticks = HEAL_TICKS

    # ------------------------------------------------------------------ services
    @async_service
    def heal(self) -> None:
        """Heal the nearest victim in the cone: answers once it is done (SUCCESS, after 10 ticks of the
        sensor), or FAILED when there is no victim within `Heal_range` or the robot has none of the
        abilities it requires."""
        self.healing = True

    @service
    def get_robot_abilities(self) -> list[int]:
        """The robot's abilities (`Abilities`), as a list of integers."""
        return list(self.abilities)

    @service
    def get_victim_requirements(self) -> list[int]:
        """The requirements of the nearest victim in the cone; fails when there is none."""
        return list(self._nearest_victim().properties["Requirements"])

    @service
    def get_victim_severity(self) -> int:
        """The severity of the nearest victim in the cone; fails when there is none."""
        return self._nearest_victim().properties["Severity"]

    def _nearest_victim(self):
        if self.nearest is None:
            raise LookupError(f"No victim within range ({self.properties.Distance:.2f} m)")
        return self.nearest[0]


def _in_cone(v: np.ndarray, axis: np.ndarray, half_angle: float) -> bool:
    n = float(np.linalg.norm(v))
    return n == 0.0 or math.acos(max(-1.0, min(1.0, float(axis @ v) / n))) <= half_angle


def _descends(m, body: int, ancestor: int) -> bool:
    while body > 0:
        body = int(m.body_parentid[body])
        if body == ancestor:
            return True
    return False


COMPONENT = SearchAndRescue
