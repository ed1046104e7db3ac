"""The environment's display settings (morsec.kits.display): `morsec render`'s pixels change as each one says,
a run names in one warning line those it cannot show, set_debug turns on the DEBUG log, the web viewer's
state is read back from the viewer itself, and the table of docs/running.md is the declared one. The native
viewer under Xvfb is in test_view_native.py."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import yaml
from runtime_helpers import free_port, wait_until

from morsec.kits import display
from morsec.kits.png import read_png

ROOT = Path(__file__).resolve().parent.parent
MORSEC = Path(sys.executable).with_name("morsec")
CAMERA = {"location": [4.0, -4.0, 2.5], "rotation": [1.1, 0.0, 0.7854]}  # looks at the robot, at the origin
WIDTH, HEIGHT = 160, 120
FLOOR = slice(70, 120)  # the lower rows: ground only (the robot is in rows 44-58)


def scene_text(**environment) -> str:
    env = {"name": "empty", "camera": CAMERA, **environment}
    return yaml.safe_dump({"environment": env, "robots": [{"name": "robot", "type": "atrv"}]}, sort_keys=False)


def render(tmp_path: Path, picture: str, **environment) -> tuple[np.ndarray, str]:
    (tmp_path / f"{picture}.yaml").write_text(scene_text(**environment))
    result = subprocess.run([str(MORSEC), "render", f"{picture}.yaml", "-o", f"{picture}.png", "--width", str(WIDTH),
                             "--height", str(HEIGHT)], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    return read_png(tmp_path / f"{picture}.png").astype(int), result.stderr


def red(image: np.ndarray) -> np.ndarray:
    """The ATRV's red body."""
    return (image[:, :, 0] > 120) & (image[:, :, 1] < 60) & (image[:, :, 2] < 60)


def changed(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.abs(a - b).sum(axis=2) > 60


@pytest.fixture(scope="module")
def material(tmp_path_factory) -> np.ndarray:
    """The default picture: MuJoCo's full rendering (viewport MATERIAL)."""
    image, stderr = render(tmp_path_factory.mktemp("material"), "material")
    assert "display settings" not in stderr  # nothing to warn about
    assert red(image).sum() > 30
    return image


def test_boundbox_draws_the_bodies_boxes_instead_of_their_shapes(tmp_path, material):
    image, _ = render(tmp_path, "boxes", viewport={"shade": "BOUNDBOX"})
    assert red(image).sum() == 0  # the robot's shapes are gone ...
    green = (image[:, :, 1] > 150) & (image[:, :, 0] < 100)  # ... its bounding boxes drawn (MuJoCo draws them green)
    rows, cols = np.nonzero(green)
    assert green.sum() > 100 and 35 < rows.mean() < 70 and 60 < cols.mean() < 100  # where the robot was (measured: 251)


def test_solid_drops_the_textures(tmp_path, material):
    """The checkered floor becomes one flat colour."""
    image, _ = render(tmp_path, "solid", viewport={"shade": "SOLID"})
    assert material[FLOOR].reshape(-1, 3).std(axis=0).mean() > 3  # measured 7.5: two colours of squares
    assert image[FLOOR].reshape(-1, 3).std(axis=0).mean() < 0.5  # measured 0
    assert red(image).sum() > 30  # the robot keeps its colour


def test_textured_keeps_the_textures_without_shadows_and_reflections(tmp_path):
    """In the sandbox (its sun casts shadows) MATERIAL and TEXTURED differ over most of the lit floor; the
    floor stays checkered."""
    textured, _ = render(tmp_path, "textured", name="sandbox", viewport={"shade": "TEXTURED"})
    lit, _ = render(tmp_path, "lit", name="sandbox")
    assert changed(textured, lit).mean() > 0.3  # measured 0.8
    assert textured[FLOOR].reshape(-1, 3).std(axis=0).mean() > 3


def test_show_physics_draws_the_collision_shapes_over_the_robot(tmp_path, material):
    image, _ = render(tmp_path, "physics", show_physics=True)
    assert red(image).sum() < 0.2 * red(material).sum()  # the grey collision shapes cover the red body
    diff = changed(image, material)
    rows, cols = np.nonzero(diff)
    assert 0.003 < diff.mean() < 0.1 and 35 < rows.mean() < 70 and 60 < cols.mean() < 100  # at the robot only


def test_the_camera_pose_is_the_environments(tmp_path, material):
    """place_camera twice as far: the robot covers about a quarter of the pixels; aim_camera turned left
    (yaw +0.15 rad): the robot moves right in the picture."""
    far, _ = render(tmp_path, "far", camera={**CAMERA, "location": [8.0, -8.0, 5.0]})
    assert 0.1 * red(material).sum() < red(far).sum() < 0.45 * red(material).sum()
    turned, _ = render(tmp_path, "turned", camera={**CAMERA, "rotation": [1.1, 0.0, 0.7854 + 0.15]})
    shift = np.nonzero(red(turned))[1].mean() - np.nonzero(red(material))[1].mean()
    assert shift > 10, shift


def test_side_by_side_stereo_draws_both_eyes(tmp_path, material):
    image, stderr = render(tmp_path, "stereo", stereo="SIDEBYSIDE")
    cols = np.nonzero(red(image))[1]
    assert (cols < WIDTH * 0.4).sum() > 10 and (cols > WIDTH * 0.6).sum() > 10  # one robot in each half
    assert (np.nonzero(red(material))[1] < WIDTH * 0.4).sum() == 0  # one robot, in the middle, otherwise
    assert "display settings" not in stderr


def test_render_names_what_it_cannot_show_in_one_line(tmp_path):
    _, stderr = render(tmp_path, "anaglyph", stereo="ANAGLYPH", show_framerate=True, viewport={
        "shade": "WIREFRAME", "clip_end": 50.0})
    lines = [line for line in stderr.splitlines() if "display settings" in line]
    assert lines == ["WARNING morsec.display: display settings morsec render cannot show: viewport.clip_end, "
                     "stereo (ANAGLYPH) (docs/running.md#display-settings says which viewer shows which)"]


def run_headless(tmp_path: Path, **environment) -> subprocess.CompletedProcess:
    (tmp_path / "s.yaml").write_text(scene_text(**environment))
    return subprocess.run([str(MORSEC), "run", "s.yaml", "--duration", "0.5", "--time-strategy", "fixed_step",
                           "--service-port", "0", "--port-base", "0"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=120)


def test_a_run_without_a_viewer_names_the_settings_it_ignores_and_logs_at_debug_level(tmp_path):
    result = run_headless(tmp_path, show_framerate=True, show_physics=True, auto_start=False, stereo="SIDEBYSIDE",
                          debug=True, viewport={"shade": "WIREFRAME"})
    assert result.returncode == 0, result.stderr
    lines = [line for line in result.stderr.splitlines() if "display settings" in line]
    assert lines == ["WARNING morsec.display: display settings a run without a viewer cannot show: viewport.shade, "
                     "show_framerate, show_physics, auto_start, stereo (SIDEBYSIDE) (docs/running.md#display-settings "
                     "says which viewer shows which)"]
    assert "DEBUG morsec.runtime: 1 robots, 0 components, 60 Hz, fixed_step" in result.stderr.splitlines()
    assert "PAUSED" not in result.stdout  # auto_start needs a viewer to start it: a run without one starts


def test_a_run_with_default_settings_warns_nothing_and_logs_no_debug(tmp_path):
    """fastmode (wireframes in a viewer) included: every MORSE test sets it, for speed."""
    result = run_headless(tmp_path, fastmode=True)
    assert result.returncode == 0, result.stderr
    assert "display settings" not in result.stderr and "DEBUG" not in result.stderr


def test_the_docs_table_is_the_declared_one():
    page = (ROOT / "docs" / "running.md").read_text(encoding="utf-8")
    assert display.markdown() in page, ("docs/running.md's display tables differ from morsec.kits.display: paste "
                                        "`python -c 'from morsec.kits.display import markdown; print(markdown())'`")
    for setting in display.SETTINGS:  # every setting the warnings name is in the table
        assert f"| `{setting.name}` |" in page


# ---------------------------------------------------------------------------------------------- web viewer

def test_web_viewer_draws_as_the_settings_say_and_its_panel_runs_the_simulation(tmp_path):
    """In process: the viewer's own options (read back from it), the morsec panel's rows once a browser is
    on the page (NetImgui through /ui, as test_keyboard's browser), and space runs the paused simulation."""
    import mujoco
    from components.test_keyboard import BrowserKeys
    from websockets.sync.client import connect

    from morsec.app.project import build_scene
    from morsec.runtime.simulation import RunOptions, Simulation

    (tmp_path / "s.yaml").write_text(yaml.safe_dump({
        "environment": {"name": "empty", "camera": CAMERA, "show_framerate": True, "show_debug": True,
                        "show_physics": True, "auto_start": False, "viewport": {"shade": "WIREFRAME"}},
        "robots": [{"name": "robot", "type": "atrv", "translate": [1.0, 2.0, 0.0],
                    "components": [{"name": "pose", "type": "pose"}]}]}))
    build = build_scene(tmp_path / "s.yaml", tmp_path / "build")
    port = free_port()
    sim = Simulation(build, RunOptions(service_port=0, port_base=0, view="web", view_port=port))
    try:
        view = sim.view
        assert view is not None and view.paused
        panel = view.panel
        wait_until(lambda: panel.model_shown, timeout=30)
        viewer = panel.viewer
        assert viewer.render_flags.flags[mujoco.mjtRndFlag.mjRND_WIREFRAME] == 1
        assert viewer.vis_options.geomgroup[3] == 1 and viewer.vis_options.flags[mujoco.mjtVisFlag.mjVIS_CONTACTPOINT]
        assert viewer.camera.type == mujoco.mjtCamera.mjCAMERA_FIXED
        assert viewer.camera.fixedcamid == mujoco.mj_name2id(sim.model, mujoco.mjtObj.mjOBJ_CAMERA, "morsec_default")
        sim.frame()  # the pose sensor's first reading
        with connect(f"ws://127.0.0.1:{port}/ui?sid=test", max_size=None, open_timeout=20) as ws:
            browser = BrowserKeys(ws)

            def drawn() -> dict:
                view.sync()
                time.sleep(0.04)
                return dict(panel.drawn)
            rows = wait_until(lambda: (d := drawn()) and "frame rate" in d and d, timeout=20)
            assert rows["PAUSED (space or the Run button runs it)"] == ""
            assert rows["robot"].startswith("x 1.00  y 2.00  z ")
            assert rows["robot.pose"].startswith("x 1  y 2  z ")
            assert set(rows) >= {"simulated time", "real-time factor"}
            browser.hold({SPACE}, 0.3)
            browser.hold(set(), 0.2)
            wait_until(lambda: drawn() is not None and not view.paused, timeout=10)
            browser.close()
    finally:
        sim.close()


SPACE = 12  # NetImgui's key number of the space bar (test_keyboard: UP_ARROW is 3)
