from morsec.component import ComputationModeProperties, DataField, Sensor

AIR_DENSITY = 1.225  # kg/m^3, sea level (MORSE's constant)


class Airspeed(Sensor):
    """Differential pressure of a pitot tube pointing along the sensor's +x axis: 0.5 rho v^2, v being the
    velocity along that axis (rho = 1.225 kg/m^3, still air; valid below Mach 1). With physics
    (`ComputationMode` Velocity) v is the robot's linear velocity seen in the sensor's frame; in Position
    mode, the sensor's displacement since the previous tick over the time elapsed, along its x axis."""

    short_descr = "Differential pressure of a pitot tube (airspeed)"
    builder_name = "Airspeed"
    frequency = 60.0

    class Properties(ComputationModeProperties):
        pass

    data = (
        DataField("diff_pressure", 0.0, "float", "differential (dynamic) pressure 0.5 rho v^2 along the sensor's "
                  "x axis, Pa"),
    )

    def start(self):
        mode = self.properties.ComputationMode
        self.mode = ("Velocity" if self.robot.free else "Position") if mode == "Automatic" else mode
        self.previous_time = self.sim.clock.elapsed
        self.previous_pos = self.position().copy()

    def airspeed(self) -> float | None:
        """The velocity along the sensor's x axis, m/s (None in Position mode when no time has passed)."""
        axis = self.rotation()[:, 0]
        if self.mode == "Velocity":
            linear, _ = self.robot.velocity()  # world frame: MORSE reads the robot's, not the sensor's
            return float(axis @ linear)
        now = self.sim.clock.elapsed
        dt = now - self.previous_time
        if dt < 1e-9:
            return None
        pos = self.position().copy()
        speed = float(axis @ (pos - self.previous_pos)) / dt
        self.previous_time, self.previous_pos = now, pos
        return speed

    def default_action(self):
        v = self.airspeed()
        if v is not None:
            self.local_data["diff_pressure"] = 0.5 * AIR_DENSITY * v * v


COMPONENT = Airspeed
