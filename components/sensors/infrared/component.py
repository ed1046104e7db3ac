from morsec.component.catalogue import component_class

LaserScanner = component_class("sensors", "laser_scanner")


class Infrared(LaserScanner):
    """Infra-red proximity sensor (MORSE's `Infrared` builder): a narrow fan of 21 rays, 1 degree apart
    over 20 degrees, up to 2 m, 10 scans per second. See `laser_scanner` for the fields, levels and ray
    geometry."""

    short_descr = "Infra-red proximity sensor: 20 deg, 1 deg, 2 m, 10 Hz (21 rays)"
    builder_name = "Infrared"
    frequency = 10.0

    class Properties(LaserScanner.Properties):
        laser_range: float = 2.0
        scan_window: float = 20.0
        resolution: float = 1.0
        Visible_arc: bool = True


COMPONENT = Infrared
