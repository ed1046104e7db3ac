"""Cost of one `hokuyo` scan inside morsec against a bare `mujoco.mj_multiRay` call with the same 1081
rays in the same scene (target: ratio <= 1.3).

The scene: an ATRV with a Hokuyo 0.6 m above the floor in `indoors-1/boxes` (a closed hall with boxes;
`empty` plus a ring of boxes when that environment is missing), plus a few boxes around the robot. Both
sides cast from the same point, with the same world-frame ray directions, the same geom group mask and
cutoff, and find the same ranges (checked). The morsec side is the component's whole `default_action`:
rotating the rays into the world, parking the robot's own geoms in the hidden group and back, the cast,
miss handling, point_list / range_list arrays. The bare side tests the robot's own geoms too (they are
never hit from up there), which makes it slightly slower per ray than morsec's cast.

Batches of `--calls` calls alternate (bare, morsec, bare, ...) so that both see the same machine load;
the best batch of each is kept. The line "for reference" is what turning the arrays into Python lists
costs; that is paid only when a stream publishes, by the encoder, next to the JSON encoding itself.

    .venv/bin/python benchmarks/laser.py [--calls 200] [--repeats 40]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import mujoco
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from timing import batch, compare  # noqa: E402  (benchmarks/timing.py)

from morsec.component.catalogue import load_catalogue  # noqa: E402
from morsec.testing import simulate  # noqa: E402

BOXES = [  # (name, centre, size): around the robot at the origin, in both environments
    ("crate_front", [4.0, 0.5, 0.5], [1.0, 1.0, 1.0]),
    ("crate_left", [1.0, 3.0, 0.4], [0.8, 0.8, 0.8]),
    ("crate_right", [-1.5, -2.5, 0.6], [0.6, 1.2, 1.2]),
    ("pillar", [-2.5, 1.5, 1.0], [0.3, 0.3, 2.0]),
]
RING = [(f"ring_{k}", [12.0 * np.cos(a), 12.0 * np.sin(a), 1.0], [1.5, 1.5, 2.0])
        for k, a in enumerate(np.linspace(0.0, 2.0 * np.pi, 12, endpoint=False))]


def scene_yaml() -> str:
    envs = load_catalogue().ids("environments")
    env = "indoors-1/boxes" if "indoors-1/boxes" in envs else "empty"
    boxes = BOXES + ([] if env != "empty" else RING)
    objects = "\n".join(f"  - {{name: {n}, type: box, translate: {list(map(float, c))}, size: {s}}}"
                        for n, c, s in boxes)
    return f"""environment: {{name: {env}, time: {{strategy: fixed_step}}}}
robots:
  - name: robot
    type: atrv
    components:
      - {{name: hokuyo, type: hokuyo, translate: [0.2, 0.0, 0.5]}}
objects:
{objects}
"""


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--calls", type=int, default=200)
    parser.add_argument("--repeats", type=int, default=40)
    args = parser.parse_args(argv)

    with tempfile.TemporaryDirectory() as tmp, simulate(scene_yaml(), Path(tmp)) as sim:
        sim.step(6)  # the first scan is done; the robot has settled a little
        laser = sim.component("robot.hokuyo")
        m, d, b = sim.sim.model, sim.sim.data, laser.body_id
        mask = np.array([1, 1, 0, 1, 1, 0], dtype=np.uint8)  # collision geometry: no visual-only geoms
        laser_range = float(laser.properties.laser_range)

        # the bare call: the same rays (world frame), origin, mask and cutoff, preallocated buffers
        pnt = d.xpos[b].copy()
        vec = np.ascontiguousarray(laser.ray_directions() @ d.xmat[b].reshape(3, 3).T).reshape(-1)
        nray = vec.size // 3
        geomid = np.empty(nray, dtype=np.int32)
        dist = np.empty(nray)

        def bare():
            mujoco.mj_multiRay(m, d, pnt, vec, mask, 1, -1, geomid, dist, None, nray, laser_range)

        bare()
        laser.default_action()
        ranges = np.array(laser.local_data["range_list"])
        expected = np.where((dist < 0) | (dist > laser_range), laser_range, dist)
        assert nray == 1081 == len(ranges), (nray, len(ranges))
        assert np.allclose(ranges, expected), "morsec and the bare call disagree"
        hits = int(np.count_nonzero(dist >= 0))

        compare(bare, laser.default_action, args.calls, 2)  # warm up
        t_bare, t_morsec = compare(bare, laser.default_action, args.calls, args.repeats)
        # not part of the scan: what an encoder pays to turn the arrays into Python lists before JSON
        t_lists = min(batch(lambda: (laser.local_data["point_list"].tolist(),
                                     laser.local_data["range_list"].tolist()), args.calls) for _ in range(5))

    print(f"scene: {m.ngeom} geoms, {nray} rays, {hits} hits, MuJoCo {mujoco.__version__}")
    print(f"bare mj_multiRay      {t_bare * 1e6:9.1f} us/scan")
    print(f"morsec hokuyo scan    {t_morsec * 1e6:9.1f} us/scan  (default_action)")
    ratio = t_morsec / t_bare
    print(f"ratio                 {ratio:9.2f}  (target <= 1.3)")
    print(f"(for reference: .tolist() of point_list + range_list, paid only when a stream publishes: "
          f"{t_lists * 1e6:.1f} us)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
