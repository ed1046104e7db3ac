"""The Earth's magnetic field from the World Magnetic Model (the maintained `pygeomag` package), for the
magnetometer and the IMU."""

from __future__ import annotations

import datetime
from functools import lru_cache

import numpy as np


def decimal_year(day: datetime.date) -> float:
    start = datetime.date(day.year, 1, 1)
    length = (datetime.date(day.year + 1, 1, 1) - start).days
    return day.year + (day - start).days / length


@lru_cache(maxsize=8)
def _wmm(release: str):
    from pygeomag import GeoMag
    return GeoMag(coefficients_file=f"wmm/WMM_{release}.COF")


def wmm_release(year: float) -> str:
    """The WMM release for a date: the one whose epoch precedes it (WMM2010 ... WMM2025, the earliest and the
    latest extrapolated past their five years). From 2015 to 2020 it is WMM2015 as first published, the one
    MORSE shipped (its tests' figures are WMM2015's own test values), not the WMM2015v2 of 2019."""
    return "2025" if year >= 2025 else "2020" if year >= 2020 else "2015" if year >= 2015 else "2010"


def wmm_ned(lat: float, lon: float, alt_m: float, year: float) -> tuple[float, float, float]:
    """(north, east, down) field at a geodetic point (altitude above the WGS84 ellipsoid), nT, from the
    release `wmm_release` picks."""
    release = wmm_release(year)
    r = _wmm(release).calculate(glat=lat, glon=lon, alt=alt_m / 1000.0, time=year,
                                allow_date_outside_lifespan=True)
    return float(r.x), float(r.y), float(r.z)


def field_in_scene(geo, position, year: float) -> np.ndarray:
    """The field at a scene position, as a vector of the scene frame (nT)."""
    lat, lon, alt = geo.to_geodetic(position)
    north, east, down = wmm_ned(lat, lon, alt, year)
    return geo.from_enu([east, north, -down])
