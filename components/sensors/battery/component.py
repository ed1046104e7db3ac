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
        self.previous_time = self.sim.clock.elapsed  # simulated seconds (exact, unlike epoch timestamps)

    def default_action(self):
        now = self.sim.clock.elapsed
        dt, self.previous_time = now - self.previous_time, now
        rate = self.properties.DischargingRate
        charge = float(self.local_data["charge"])
        if self.sim.zones_at(self.position(), CHARGING_ZONE):
            charge += dt * rate
            status = "Charging"
            if charge >= 100.0:
                charge, status = 100.0, "Charged"
        else:
            charge = max(0.0, charge - dt * rate)
            status = "Discharging"
        self.local_data["charge"] = float(charge)
        self.local_data["status"] = status


COMPONENT = Battery
