"""Frames per second of a 320 x 240 `video_camera` and of a 320 x 240 `depth_camera` inside morsec against
`mujoco.Renderer` rendering the same MJCF camera of the same model directly (target: ratio <= 1.2).

The scene: a fixed holder 1 m above the floor of `indoors-1/boxes` (`empty` plus a ring of boxes when that
environment is missing) carrying both cameras, looking along +x at a few boxes. The morsec side is each
component's whole tick (`default_action`): the camera poses (mj_camlight), its clip planes, the render
through the shared renderer of its size, and for the video camera the RGBA picture (alpha added, rows as
Vertical_Flip says), for the depth camera the depth image turned into float32 points in the optical
frame. The bare side is a `mujoco.Renderer` of the same size on the same model: `update_scene(camera)` +
`render()` (RGB, or depth), with the same clip planes and the same scene flags as the sensor (no shadows,
no reflections: MuJoCo's defaults have both, see the reference line) — checked to give the same pixels.

Batches of `--frames` frames alternate (bare, morsec, bare, ...) so that both see the same machine load;
the best batch of each is kept. The line "for reference" is what publishing costs when a client listens
(base64 + JSON of the socket message), paid by the stream, not by the tick.

    .venv/bin/python benchmarks/camera.py [--frames 10] [--repeats 8]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import mujoco  # noqa: E402
from timing import batch, compare  # noqa: E402  (benchmarks/timing.py)

import morsec  # noqa: E402,F401  (chooses MUJOCO_GL before mujoco is imported)
from morsec.component.catalogue import load_catalogue  # noqa: E402
from morsec.middleware.socket_streams import encode  # noqa: E402
from morsec.testing import simulate  # noqa: E402

WIDTH, HEIGHT = 320, 240
BOXES = [("crate_front", [4.0, 0.5, 0.5], [1.0, 1.0, 1.0]), ("crate_left", [3.0, 2.0, 0.4], [0.8, 0.8, 0.8]),
         ("crate_right", [5.0, -1.5, 0.6], [0.6, 1.2, 1.2]), ("pillar", [6.0, 0.0, 1.0], [0.3, 0.3, 2.0])]
RING = [(f"ring_{k}", [12.0 * np.cos(a), 12.0 * np.sin(a), 1.0], [1.5, 1.5, 2.0])
        for k, a in enumerate(np.linspace(0.0, 2.0 * np.pi, 12, endpoint=False))]


def scene_yaml() -> str:
    envs = load_catalogue().ids("environments")
    env = "indoors-1/boxes" if "indoors-1/boxes" in envs else "empty"
    boxes = BOXES + ([] if env != "empty" else RING)
    objects = "\n".join(f"  - {{name: {n}, type: box, translate: {list(map(float, c))}, size: {s}}}"
                        for n, c, s in boxes)
    size = f"cam_width: {WIDTH}, cam_height: {HEIGHT}"
    return f"""environment: {{name: {env}, time: {{strategy: fixed_step}}}}
robots:
  - name: holder
    type: fake_robot
    translate: [0.0, 0.0, 1.0]
    components:
      - {{name: video, type: video_camera, properties: {{{size}}}}}
      - {{name: depth, type: depth_camera, properties: {{{size}}}}}
objects:
{objects}
"""


def bare_renderer(m, d, camera, *, depth: bool, near: float, far: float, effects: bool = False):
    """A plain mujoco.Renderer drawing `camera`, with the sensor's clip planes and scene flags."""
    renderer = mujoco.Renderer(m, HEIGHT, WIDTH)
    if depth:
        renderer.enable_depth_rendering()
    extent = m.stat.extent

    def render():
        saved = (m.vis.map.znear, m.vis.map.zfar)
        m.vis.map.znear, m.vis.map.zfar = near / extent, far / extent
        try:
            renderer.update_scene(d, camera=camera)
            renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = effects
            renderer.scene.flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = effects
            return renderer.render()
        finally:
            m.vis.map.znear, m.vis.map.zfar = saved

    return renderer, render


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--frames", type=int, default=10)
    parser.add_argument("--repeats", type=int, default=8)
    args = parser.parse_args(argv)

    results = {}
    with tempfile.TemporaryDirectory() as tmp, simulate(scene_yaml(), Path(tmp)) as sim:
        sim.step(3)  # the cameras have started and grabbed once
        m, d = sim.sim.model, sim.sim.data
        mujoco.mj_camlight(m, d)
        for name in ("video", "depth"):
            cam = sim.component(f"holder.{name}")
            p = cam.properties
            depth = name == "depth"
            renderer, bare = bare_renderer(m, d, f"holder.{name}", depth=depth, near=p.cam_near, far=p.cam_far)
            _, bare_default = bare_renderer(m, d, f"holder.{name}", depth=depth, near=p.cam_near, far=p.cam_far,
                                            effects=True)
            cam.default_action()
            reference = bare()
            if depth:  # the same depth, hence the same points
                z = reference[::-1][cam.rows].reshape(-1)
                hit = z < p.cam_far * (1 - 1e-4)
                assert np.allclose(cam.local_data["points"][:, 2], z[hit]), "morsec and the bare render disagree"
            else:
                assert np.array_equal(cam.local_data["image"][..., :3], reference), "the pictures differ"
            compare(bare, cam.default_action, 2, 1)  # warm up
            t_bare, t_morsec = compare(bare, cam.default_action, args.frames, args.repeats)
            t_default = min(batch(bare_default, args.frames) for _ in range(2))
            t_publish = min(batch(lambda cam=cam: encode(cam.serialize()), args.frames) for _ in range(3))
            results[name] = (t_bare, t_morsec, t_default, t_publish)
            renderer.close()

    print(f"{WIDTH} x {HEIGHT}, MuJoCo {mujoco.__version__}, MUJOCO_GL={__import__('os').environ.get('MUJOCO_GL')}, "
          f"{m.ngeom} geoms")
    for name, (t_bare, t_morsec, t_default, t_publish) in results.items():
        kind = "video_camera" if name == "video" else "depth_camera"
        print(f"{kind}:")
        print(f"  bare mujoco.Renderer  {1 / t_bare:8.1f} fps  ({t_bare * 1e3:.2f} ms/frame)")
        print(f"  morsec {kind:<14} {1 / t_morsec:8.1f} fps  ({t_morsec * 1e3:.2f} ms/frame, default_action)")
        print(f"  ratio                 {t_morsec / t_bare:8.2f}  (time per frame, morsec / bare; target <= 1.2)")
        print(f"  (for reference: bare with MuJoCo's default flags, shadows and reflections on: "
              f"{1 / t_default:.1f} fps; publishing one message, base64 + JSON: {t_publish * 1e3:.2f} ms)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
