from morsec.component.catalogue import component_class

LaserScanner = component_class("sensors", "laser_scanner")


class Hokuyo(LaserScanner):
    """Hokuyo laser range scanner (MORSE's `Hokuyo` builder, a UTM-30LX): one flat layer of 1081 rays,
    0.25 degree apart over 270 degrees, up to 30 m, 10 scans per second. Ray 0 points 135 degrees to the
    right, ray 540 straight ahead (+x), ray 1080 135 degrees to the left. See `laser_scanner` for the
    fields, levels and ray geometry."""

    short_descr = "Hokuyo laser scanner: 270 deg, 0.25 deg, 30 m, 10 Hz (1081 rays)"
    builder_name = "Hokuyo"
    frequency = 10.0

    class Properties(LaserScanner.Properties):
        laser_range: float = 30.0
        scan_window: float = 270.0
        resolution: float = 0.25


COMPONENT = Hokuyo
