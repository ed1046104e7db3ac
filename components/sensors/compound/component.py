from typing import ClassVar

from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor


class CompoundSensor(Sensor):
    """One message holding the data of several sensors: `{"timestamp": t, "<robot.sensor>": that
    sensor's local_data, ...}`, keyed by fully-qualified name in the order `sensors` lists them (the
    format ArduPilot's SITL reads from MORSE). It ticks after the other sensors of the frame, so each
    message carries their latest values; their services are not exposed through it."""

    short_descr = "Several sensors' data in one message, keyed by full name"
    builder_name = "CompoundSensor"
    frequency = 60.0
    tick_last: ClassVar[bool] = True  # the simulation ticks it after the sensors it gathers

    class Properties(ComponentProperties):
        sensors: str = Field("", description="comma-separated fully-qualified names of the sensors to merge, "
                             "e.g. 'quad.imu,quad.gps,quad.pose'")

    data = ()
    extra_field = DataField("<robot.sensor>", {}, "dict", "for each sensor listed, in the order listed: that "
                            "sensor's latest data (its own timestamp first)")

    def start(self):
        names = [s.strip() for s in self.properties.sensors.split(",") if s.strip()]
        if not names:
            raise ValueError(f"compound sensor {self.name}: property 'sensors' lists no sensor")
        known = {c.fqn: c for c in self.sim.components}
        for fqn in names:
            comp = known.get(fqn)
            if comp is None or comp.kind != "sensor" or fqn == self.name:
                from morsec.errors import did_you_mean
                sensors = [c.fqn for c in self.sim.components if c.kind == "sensor" and c.fqn != self.name]
                raise ValueError(f"compound sensor {self.name}: no sensor named {fqn!r}"
                                 f"{did_you_mean(fqn, sensors)}")
        self.sources = names

    def default_action(self):
        for fqn in self.sources:  # the sensors' own dicts: serialised when this message is sent
            self.local_data[fqn] = self.sim.by_name[fqn].instance.local_data


COMPONENT = CompoundSensor
