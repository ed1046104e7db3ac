"""MORSE's LaserScanner: a fan of rays cast from the sensor centre into the scene's collision geometry.

One `mujoco.mj_multiRay` call per scan, no Python loop over rays:

* ray directions are computed once, at start, in the sensor frame (MORSE builds its "Arc_" mesh once:
  `resolution`, `scan_window` and the layer properties are read at start; `laser_range` is read at
  every scan, so `set_property('laser_range', ...)` takes effect at the next scan);
* each scan's rays are rotated into the world with the sensor's orientation at the scan (one 3x3 product)
  and cast from its origin at the scan with `cutoff = laser_range`;
* rays see collision geometry only: the geom group mask excludes group 2 (the robots' visual-only
  geoms and the components' own models), and the geoms of the robot carrying the sensor (every body
  of its kinematic tree, not only the one `bodyexclude` could skip) are moved to group 5 for the
  duration of the call and put back right after, so the scanner never sees its own robot. Group 5
  geoms are therefore never seen by a laser;
* results are converted with numpy: a hit point in the sensor frame is the ray's unit direction (sensor
  frame) times the hit distance, because the rays start at the sensor's origin;
* the rays are cast when the data is read (SampledSensor), on the world as it was at the scan: a scan copies
  what `mj_multiRay` reads that the run changes (MjData's geom poses and bodies' inertial frames, which the
  bounding volumes follow; the model's geom groups) and the sensor's position and rotation, as byte copies
  between memoryviews (a scan ticks up to every frame; np.copyto and the rays' rotation were 2 µs of it); a
  read rotates the rays, puts those copies in place for the cast and the live values back after it. A scan
  nobody reads rotates and casts nothing
  (tests/test_sampled_sensors.py checks, on the installed MuJoCo, that a cast reads nothing else of MjData).
  A cast also skips geoms whose colour or material is fully transparent (the model's rgba alphas): nothing
  changes those during a run; something that did would have to be copied with the rest.
  In a model with flexes (which morsec's compiler does not write; a user's MJCF template could), whose
  vertices a cast reads too, unchecked, the rays are cast at the scan.

In `local_data` the three lists are numpy arrays (point_list N x 3, range_list and remission_list N),
fresh at every scan: building ~4000 Python objects per Hokuyo scan would cost more than the ray cast
itself. Every middleware writes them as plain lists (the socket stream's JSON is MORSE's exactly:
`"point_list": [[x, y, z], ...]`); in-process readers (modifiers, tests) index them like lists or call
`.tolist()`.
"""

from __future__ import annotations

import math

import mujoco
import numpy as np
from pydantic import Field

from morsec.component import ComponentProperties, DataField, Level, SampledSensor

VISUAL_GROUP = 2  # robots' visual-only geoms and components' models (class "visual" / "component")
HIDDEN_GROUP = 5  # where the carrying robot's own geoms are parked during a scan
RAY_MASK = np.array([0 if g in (VISUAL_GROUP, HIDDEN_GROUP) else 1 for g in range(mujoco.mjNGROUP)],
                    dtype=np.uint8)
DEFAULT_SPECULAR = 0.5  # MuJoCo's material default: what a geom without a material is rendered with


def arc_directions(resolution: float, scan_window: float, layers: int = 1, layer_separation: float = 0.0,
                   layer_offset: float = 0.0) -> np.ndarray:
    """Unit ray directions (N x 3, sensor frame) of MORSE's laser arc (`create_laser_arc`).

    Within a layer the azimuth goes from -scan_window/2 to +scan_window/2 inclusive in `resolution`
    steps (index 0 is the rightmost ray, on the -y side); the sensor looks along +x. With several
    layers, layer 0 is the highest, at elevation layer_separation * (layers - 1) / 2, each next one
    layer_separation lower, and the even layers (0, 2, ...) are shifted by +layer_offset in azimuth.
    All angles in degrees. A single layer is flat (elevation 0) and not offset, as MORSE's Sick and
    Hokuyo, whose builders set no layer properties."""
    if resolution <= 0 or scan_window < 0:
        raise ValueError("resolution must be > 0 and scan_window >= 0")
    per_layer = int(math.floor(scan_window / resolution + 1e-6)) + 1
    steps = np.arange(per_layer, dtype=float) * resolution
    rows = []
    top = layer_separation * (layers - 1) / 2.0 if layers > 1 else 0.0
    for index in range(layers):
        offset = layer_offset if (layers > 1 and index % 2 == 0) else 0.0
        azimuth = np.radians(-scan_window / 2.0 + offset + steps)
        elevation = math.radians(top - index * layer_separation)
        rows.append(np.column_stack((math.cos(elevation) * np.cos(azimuth),
                                     math.cos(elevation) * np.sin(azimuth),
                                     np.full(per_layer, math.sin(elevation)))))
    return np.ascontiguousarray(np.vstack(rows))


class LaserScannerProperties(ComponentProperties):
    laser_range: float = Field(30.0, gt=0, description="distance from the sensor centre up to which objects are "
                               "detected, m; can be changed while running (set_property)")
    resolution: float = Field(1.0, gt=0, description="angle between two rays of a layer, deg (fixed at start)")
    scan_window: float = Field(180.0, ge=0, le=360, description="full angle covered by a layer, deg (fixed at start)")
    Visible_arc: bool = Field(False, description="MORSE shows the arc in the 3D view; accepted, no effect headless")
    layers: int = Field(1, ge=1, description="number of scanning planes (fixed at start)")
    layer_separation: float = Field(0.8, ge=0, description="elevation between two consecutive layers, deg")
    layer_offset: float = Field(0.125, description="azimuth shift of the even layers (0, 2, ...), deg; "
                                "only with layers > 1")


class LaserScanner(SampledSensor):
    """A laser range scanner: rays cast in a fan from the sensor's centre, in its x-y plane, looking along
    +x. `range_list[i]` is the distance to the first collision geometry hit by ray i (`laser_range` on a
    miss) and `point_list[i]` the hit point in the sensor frame (`[0, 0, 0]` on a miss). Rays go from
    -scan_window/2 (index 0, right, -y side) to +scan_window/2 every `resolution` degrees; several layers
    are stacked in elevation, top layer first. The `rssi` level adds `remission_list`. Presets: `sick`,
    `hokuyo`, `sick_ld_mrs`, `infrared`, `velodyne_ray_cast`."""

    short_descr = "Generic laser range scanner (ray fan, layers)"
    builder_name = "LaserScanner"
    frequency = 10.0
    Properties = LaserScannerProperties
    levels = (
        Level("raw", None, "point_list and range_list", default=True),
        # MORSE's RSSILaserScanner: same class here, the level switches the remission computation on
        Level("rssi", None, "point_list, range_list and remission_list (MORSE's RSSILaserScanner)"),
    )
    data = (
        DataField("point_list", [], "list[vec3]",
                  "hit points in the sensor frame, m, one per ray in ray order; [0, 0, 0] when the ray hit "
                  "nothing within laser_range", level=("raw", "rssi")),
        DataField("range_list", [], "list[float]",
                  "distance from the sensor centre to the first obstacle of each ray, m; laser_range when "
                  "the ray hit nothing", level=("raw", "rssi")),
        DataField("remission_list", [], "list[float]",
                  "remission of each hit, 0..1: the specular intensity of the hit geom's material (0.5, "
                  "MuJoCo's default, for a geom without material); 0 when the ray hit nothing", level="rssi"),
    )

    # ---- ray geometry (sensor frame), fixed at start
    def ray_directions(self) -> np.ndarray:
        p = self.properties
        return arc_directions(p.resolution, p.scan_window, p.layers, p.layer_separation, p.layer_offset)

    def start(self) -> None:
        m = self.sim.model
        self._dirs = np.ascontiguousarray(self.ray_directions(), dtype=np.float64)
        self.nray = len(self._dirs)
        self._vec = np.empty((self.nray, 3))  # world directions, rewritten at every scan
        self._vec_flat = self._vec.reshape(-1)
        self._geomid = np.empty(self.nray, dtype=np.int32)
        self._dist = np.empty(self.nray)
        self._rssi = self.level == "rssi"
        # the carrying robot: every body of the sensor's kinematic tree (below the world)
        root = m.body_rootid[self.body_id]
        own_bodies = np.flatnonzero(m.body_rootid == root) if root != 0 else np.array([self.body_id])
        own = np.flatnonzero(np.isin(m.geom_bodyid, own_bodies) & (m.geom_group != VISUAL_GROUP))
        self._own = own if len(own) else None
        self._own_groups = m.geom_group[own].copy()
        if self._rssi:
            specular = np.full(m.ngeom + 1, 0.0)  # last slot: a miss (geom id -1)
            matid = m.geom_matid
            specular[:m.ngeom] = np.where(matid >= 0, m.mat_specular[np.maximum(matid, 0)], DEFAULT_SPECULAR)
            self._remission = specular
        # what a cast reads that the run changes, copied at each scan: MjData's geom poses and bodies' inertial
        # frames (the bodies' bounding boxes) and the geoms' groups (a waypoint's marker turns visual). None: cast
        # at the scan (flexes)
        d = self.sim.data
        self._world = None if m.nflex else [d.geom_xpos, d.geom_xmat, d.xipos, d.ximat, m.geom_group]
        self._scanned = [np.empty_like(live) for live in self._world or ()]  # the last scan's world
        self._live = [np.empty_like(live) for live in self._world or ()]  # the live world, kept during a cast
        # a scan's copy of the world, as plain byte copies between memoryviews of both sides (MjData's and the
        # model's arrays stay put): a small array's np.copyto costs four times more
        self._keep = [(_bytes(scanned), _bytes(live)) for live, scanned in zip(self._world or (), self._scanned)]
        self._from = np.empty(3)  # the sensor's position at the last scan
        self._rot = np.empty(9)  # ... and its rotation (row-major)
        self._xpos, self._xmat = d.xpos[self.body_id], d.xmat[self.body_id]
        self._scan_pose = ((_bytes(self._from), _bytes(self._xpos)), (_bytes(self._rot), _bytes(self._xmat)))
        self.local_data["point_list"] = np.zeros((self.nray, 3))
        self.local_data["range_list"] = np.full(self.nray, float(self.properties.laser_range))
        if self._rssi:
            self.local_data["remission_list"] = np.zeros(self.nray)

    # ---- one scan
    def scan_directions(self) -> np.ndarray:
        """The rays of this scan in the sensor frame (N x 3): the same at every scan (a turning scanner's
        change; they are read at the scan)."""
        return self._dirs

    def world_directions(self, dirs: np.ndarray, rot: np.ndarray) -> None:
        """Turn a scan's rays into the world frame with its rotation, into the buffer `cast` reads."""
        np.matmul(dirs, rot.T, out=self._vec)

    def cast(self, pos: np.ndarray, laser_range: float) -> tuple[np.ndarray, np.ndarray]:
        """Cast the rays of `_vec` from `pos` in the world MjData holds: (distances with -1 for misses, geom
        ids), in buffers the next cast rewrites."""
        m = self.sim.model
        own = self._own
        if own is not None:
            m.geom_group[own] = HIDDEN_GROUP
        try:
            mujoco.mj_multiRay(m, self.sim.data, pos, self._vec_flat, RAY_MASK, 1, -1, self._geomid, self._dist,
                               None, self.nray, laser_range)
        finally:
            if own is not None:
                m.geom_group[own] = self._own_groups
        return self._dist, self._geomid

    # ---- a scan keeps its rays, the sensor's pose and the world as the rays would see it; they are turned into
    # the world and cast when the data is read (SampledSensor): nothing is cast at the scans nobody reads
    def sample(self) -> tuple:
        # into buffers, not copies: only the next scan rewrites them, and its sample replaces this one
        dirs = self.scan_directions()
        laser_range = float(self.properties.laser_range)
        for scanned, live in self._scan_pose:
            scanned[:] = live
        if self._world is None:
            self.world_directions(dirs, self._rot.reshape(3, 3))
            return dirs, laser_range, *self.cast(self._from, laser_range)
        for scanned, live in self._keep:
            scanned[:] = live
        return dirs, laser_range, None, None

    def compute(self, dirs: np.ndarray, laser_range: float, dist: np.ndarray | None, geomid: np.ndarray | None) -> None:
        if dist is None:  # cast now in the scan's world
            self.world_directions(dirs, self._rot.reshape(3, 3))
            world, live = self._world or (), self._live
            for now, kept, scanned in zip(world, live, self._scanned):
                np.copyto(kept, now)
                np.copyto(now, scanned)
            try:
                dist, geomid = self.cast(self._from, laser_range)
            finally:
                for now, kept in zip(world, live):
                    np.copyto(now, kept)
        self.convert(dirs, dist, geomid if self._rssi else None, laser_range)

    def convert(self, dirs: np.ndarray, dist: np.ndarray, geomid: np.ndarray | None, laser_range: float) -> None:
        """Points, ranges (and remissions) from a cast."""
        hit = (dist >= 0.0) & (dist <= laser_range)
        points = dirs * np.where(hit, dist, 0.0)[:, None]
        points += 0.0  # a missed ray's negative direction components give -0.0: MORSE writes plain 0.0
        self.local_dict["point_list"] = points
        self.local_dict["range_list"] = np.where(hit, dist, laser_range)
        if geomid is not None:
            self.local_dict["remission_list"] = self._remission[np.where(hit, geomid, -1)]


def _bytes(array: np.ndarray) -> memoryview:
    """A C-contiguous array's bytes, as a memoryview (a slice assignment between two is a plain copy)."""
    assert array.flags["C_CONTIGUOUS"], "a scan copies contiguous arrays only"
    return array.data.cast("B")


COMPONENT = LaserScanner
