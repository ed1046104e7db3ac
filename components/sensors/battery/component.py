from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor

CHARGING_ZONE = "Charging"


class Battery(Sensor):
    """Remaining charge of the robot's battery, informative only (an empty battery does not stop the
    robot). The charge falls by `DischargingRate` percent per simulated second, whatever the robot does;
    while the sensor is inside a zone of type `Charging` it rises at the same rate, up to 100 %."""

    short_descr = "Battery charge, discharging with time, charging in Charging zones"
    builder_name = "Battery"
    frequency = 60.0

    class Properties(ComponentProperties):
        DischargingRate: float = Field(0.05, ge=0.0, description="discharge rate, percent per simulated second; "
                                       "the charge rises at the same rate in a Charging zone")

    data = (
        DataField("charge", 100.0, "float", "battery charge, percent: starts at 100, never below 0 nor above 100"),
        DataField("status", "Charged", "str", "Charged (full: at start, or filled up in a charging zone), "
                  "Charging (in a charging zone) or Discharging (elsewhere, also once empty)"),
    )

    def start(self):
        # the charge changes linearly from an anchor, (frame count, charge, charging), taken where the zone
        # changed: computed from the frames elapsed, not summed a tick at a time (floating-point error grows
        # with each sum, and MORSE's tests read the charge to the frame: `sleep(2)` is 20.0 +- 0.5 at 10 %/s)
        self.previous_frames = self.sim.clock.frames
        self.anchor: tuple[int, float, bool] | None = None

    def default_action(self):
        frames = self.sim.clock.frames
        charging = bool(self.sim.zones_at(self.position(), CHARGING_ZONE))
        if self.anchor is None or self.anchor[2] != charging:  # the time since the last tick counts in the new zone
            self.anchor = (self.previous_frames, float(self.local_data["charge"]), charging)
        self.previous_frames = frames
        since, charge, _ = self.anchor
        change = self.properties.DischargingRate * (frames - since) / self.sim.clock.frequency
        if charging:
            charge, status = charge + change, "Charging"
            if charge >= 100.0:
                charge, status = 100.0, "Charged"
        else:
            charge, status = max(0.0, charge - change), "Discharging"
        self.local_data["charge"] = float(charge)
        self.local_data["status"] = status


COMPONENT = Battery
