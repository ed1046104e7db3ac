from pydantic import Field

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
        laser_range: float = Field(30.0, gt=0, description="detection range, m; can be changed while running")
        scan_window: float = Field(100.0, ge=0, le=360, description="full angle covered by a layer, deg")
        resolution: float = Field(0.25, gt=0, description="angle between two rays of a layer, deg")
        layers: int = Field(4, ge=1, description="number of scanning planes")
        layer_separation: float = Field(0.8, ge=0, description="elevation between two consecutive layers, deg")
        layer_offset: float = Field(0.125, description="azimuth shift of the even layers (0, 2), deg")


COMPONENT = SickLDMRS
