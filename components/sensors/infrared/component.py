from pydantic import Field

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
        laser_range: float = Field(2.0, gt=0, description="detection range, m; can be changed while running")
        scan_window: float = Field(20.0, ge=0, le=360, description="full angle covered, deg (fixed at start)")
        resolution: float = Field(1.0, gt=0, description="angle between two rays, deg (fixed at start)")
        Visible_arc: bool = Field(True, description="MORSE shows the arc in the 3D view; accepted, no effect headless")


COMPONENT = Infrared
