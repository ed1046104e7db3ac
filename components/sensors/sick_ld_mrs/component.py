from morsec.component.catalogue import component_class

LaserScanner = component_class("sensors", "laser_scanner")


class SickLDMRS(LaserScanner):
    """SICK LD-MRS multi-layer laser scanner (MORSE's `SickLDMRS` builder): 4 layers of 401 rays (1604 in
    all), 0.25 degree apart over 100 degrees, up to 30 m, 4 scans per second. The layers are 0.8 degree
    apart in elevation, top first (+1.2, +0.4, -0.4, -1.2 deg); layers 0 and 2 are shifted by +0.125 deg
    in azimuth. Lists hold layer 0's rays (right to left), then layer 1's, and so on. See
    `laser_scanner` for the fields, levels and ray geometry."""

    short_descr = "SICK LD-MRS: 4 layers, 100 deg, 0.25 deg, 30 m, 4 Hz (1604 rays)"
    builder_name = "SickLDMRS"
    frequency = 4.0

    class Properties(LaserScanner.Properties):
        laser_range: float = 30.0
        scan_window: float = 100.0
        resolution: float = 0.25
        layers: int = 4
        layer_separation: float = 0.8
        layer_offset: float = 0.125


COMPONENT = SickLDMRS
