import math
import time

import numpy as np

from morsec.component import DataField, Level, SampledSensor, body_position, body_rotation
from morsec.modifiers.coordinates import POSITION_OUT
from morsec.modifiers.noise import PositionNoise

RAW = ("raw", "extended")
STILL = 1e-6  # m/s: below this horizontal speed the heading is not observable


class GPS(SampledSensor):
    """Position of the sensor: scene coordinates (`simple`), or geodetic coordinates through WGS84 with
    the East-North-Up velocity (`raw`), plus UTC date, time and heading (`extended`). The geodetic
    levels need the environment properties `longitude`, `latitude` (degrees) and `altitude` (m) of the
    scene origin, and optionally `angle_against_north` (degrees)."""

    short_descr = "GPS: scene or geodetic position, velocity, date, time and heading"
    builder_name = "GPS"
    frequency = 60.0
    modifiers = {"noise": PositionNoise, **POSITION_OUT}
    levels = (
        Level("simple", None, "position of the sensor in the scene frame", default=True),
        Level("raw", "RawGPS", "geodetic position (WGS84) and East-North-Up velocity"),
        Level("extended", "ExtendedGPS", "raw, plus UTC date and time and the heading, as a GPS sentence"),
    )
    data = (
        DataField("x", 0.0, "float", "x coordinate of the sensor, scene (world) frame, m", level="simple"),
        DataField("y", 0.0, "float", "y coordinate of the sensor, scene (world) frame, m", level="simple"),
        DataField("z", 0.0, "float", "z coordinate of the sensor, scene (world) frame, m", level="simple"),
        DataField("longitude", 0.0, "float", "longitude, degrees in [-180, 180]", level=RAW),
        DataField("latitude", 0.0, "float", "latitude, degrees in [-90, 90]", level=RAW),
        DataField("altitude", 0.0, "float", "altitude above the WGS84 ellipsoid, m (same reference as the "
                  "environment's altitude)", level=RAW),
        DataField("velocity", [0.0, 0.0, 0.0], "vec3", "velocity along East, North, Up, m/s: difference of positions "
                  "between two ticks x the nominal frequency, as MORSE (a robot moved kinematically is seen "
                  "moving)", level=RAW),
        DataField("date", "000000", "str", "UTC date of the timestamp, DDMMYY", level="extended"),
        DataField("time", "000000", "str", "UTC time of the timestamp, HHMMSS", level="extended"),
        DataField("heading", 0.0, "float", "bearing of the sensor's x axis, degrees clockwise from true north "
                  "in [0, 360); inf while the East and North velocities are both below 1e-6 m/s (not "
                  "observable standing still)", level="extended"),
    )

    reads_body_poses = True

    def sample(self):
        return self.sim.body_poses,  # the frame's copy of the bodies' poses: this sensor's is read from it when needed

    def compute(self, poses):
        local = self.local_dict
        local["x"], local["y"], local["z"] = body_position(poses, self.body_id)


class RawGPS(GPS):
    def start(self):
        self.geo = self.sim.geo  # ValueError (the simulation does not start) without geodetic properties
        self.previous = self.sim.copy_body_poses()

    def sample(self):
        # the poses now and at the previous tick: the velocity is the difference of the positions in ENU
        previous, self.previous = self.previous, self.sim.body_poses
        return self.previous, previous

    def compute(self, poses, previous):
        pos, previous_pos = body_position(poses, self.body_id), body_position(previous, self.body_id)
        enu = self.geo.to_enu(pos)
        # finite difference over the nominal period, as MORSE (a kinematic move is seen too)
        self.enu_velocity = (enu - self.geo.to_enu(previous_pos)) * self.frequency
        lat, lon, alt = self.geo.to_geodetic(pos)
        self.local_dict.update(longitude=float(lon), latitude=float(lat), altitude=float(alt),
                               velocity=[float(v) for v in self.enu_velocity])


class ExtendedGPS(RawGPS):
    def compute(self, poses, previous):
        super().compute(poses, previous)
        local = self.local_dict
        utc = time.gmtime(float(local["timestamp"]))  # the tick's: the loop stamps every tick
        local["date"] = time.strftime("%d%m%y", utc)
        local["time"] = time.strftime("%H%M%S", utc)
        east, north = self.enu_velocity[0], self.enu_velocity[1]
        if abs(east) < STILL and abs(north) < STILL:
            local["heading"] = float("inf")  # not observable standing still
        else:
            rotation = body_rotation(poses, self.body_id)  # row-major: its x axis is its first column
            forward = self.geo.to_enu(np.array((rotation[0], rotation[3], rotation[6])))
            heading = math.degrees(math.atan2(forward[0], forward[1])) % 360.0
            local["heading"] = heading if heading < 360.0 else 0.0


COMPONENT = GPS
