from pydantic import Field

from morsec.component import ComponentProperties, DataField, Sensor

MOLAR_MASS = 0.0289644  # kg/mol, dry air
GAS_CONSTANT = 8.31447  # J/(mol K)
LAPSE_RATE = 0.0065  # K/m
SEA_LEVEL_TEMPERATURE = 288.15  # K


class Barometer(Sensor):
    """Atmospheric pressure from the International Standard Atmosphere (troposphere, below 11 km):
    p = p_ref (1 - L dz / T0) ^ (g M / (R L)), where dz is the height of the sensor above its
    **initial** height and g the scene's gravity. The sensor reads `ReferencePressure` where it
    starts."""

    short_descr = "Atmospheric pressure (standard atmosphere), relative to the starting height"
    builder_name = "Barometer"
    frequency = 60.0

    class Properties(ComponentProperties):
        ReferencePressure: float = Field(101325.0, gt=0, description="pressure at the sensor's initial "
                                         "height, Pa (default: standard sea-level pressure)")

    data = (
        DataField("pressure", 0.0, "float", "atmospheric pressure, Pa"),
    )

    def start(self):
        self.reference_z = float(self.position()[2])
        gravity = float(self.sim.scene["environment"]["gravity"])
        self.exponent = gravity * MOLAR_MASS / (GAS_CONSTANT * LAPSE_RATE)

    def default_action(self):
        dz = float(self.position()[2]) - self.reference_z
        ratio = max(0.0, 1.0 - LAPSE_RATE * dz / SEA_LEVEL_TEMPERATURE)
        self.local_data["pressure"] = float(self.properties.ReferencePressure * ratio ** self.exponent)


COMPONENT = Barometer
