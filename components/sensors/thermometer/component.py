import math
import sys

import numpy as np
from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor


class Thermometer(Sensor):
    """Temperature at the sensor: a default temperature, raised by every fire source (a robot or object
    whose property named `FireTag` is set) within `Range`, each adding
    T_fire exp(-Alpha d), d being the distance from the sensor to the source's origin. A numeric value
    of the tag property is that source's temperature; otherwise `FireTemperature` is used. A source with a
    numeric `<FireTag>_Start` property (`Fire_Start`) burns from that simulated second on (a spreading
    fire, as the one of land-1/rosace_1)."""

    short_descr = "Temperature, raised by nearby objects tagged Fire"
    builder_name = "Thermometer"
    frequency = 60.0

    class Properties(ComponentProperties):
        FireTag: str = Field("Fire", description="property marking fire sources")
        DefaultTemperature: float = Field(15.0, description="temperature without fire sources, Celsius")
        FireTemperature: float = Field(200.0, description="temperature of a fire source whose tag is not a "
                                       "number, Celsius")
        Range: float = Field(float(sys.maxsize), ge=0.0, description="fire sources at this distance or "
                             "farther are ignored, m (default sys.maxsize: no limit)")
        Alpha: float = Field(0.2, ge=0.0, description="attenuation with distance, 1/m")

    data = (
        DataField("temperature", 0.0, "float", "temperature, Celsius"),
    )

    def default_action(self):
        p = self.properties
        here = self.position()
        xpos = self.sim.data.xpos
        temperature = float(p.DefaultTemperature)
        now = self.sim.clock.elapsed
        for source in self.sim.objects_with(p.FireTag):
            start = source.properties.get(f"{p.FireTag}_Start")
            if _number(start) and now < start:
                continue  # not burning yet
            distance = float(np.linalg.norm(xpos[source.body_id] - here))
            if distance >= p.Range:
                continue
            value = source.properties.get(p.FireTag)
            temperature += (float(value) if _number(value) else p.FireTemperature) * math.exp(-p.Alpha * distance)
        self.local_data["temperature"] = temperature


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


COMPONENT = Thermometer
