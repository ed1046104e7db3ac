from morsec.component.catalogue import component_class

LaserScanner = component_class("sensors", "laser_scanner")


class Sick(LaserScanner):
    """SICK LMS laser range scanner (MORSE's `Sick` builder): one flat layer of 181 rays, 1 degree apart
    over 180 degrees, up to 30 m, 10 scans per second. Ray 0 points right (-y), ray 90 straight ahead
    (+x), ray 180 left (+y). See `laser_scanner` for the fields, levels and ray geometry."""

    short_descr = "SICK LMS laser scanner: 180 deg, 1 deg, 30 m, 10 Hz (181 rays)"
    builder_name = "Sick"
    frequency = 10.0

    class Properties(LaserScanner.Properties):
        laser_range: float = 30.0
        scan_window: float = 180.0
        resolution: float = 1.0


COMPONENT = Sick
