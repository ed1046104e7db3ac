"""`morsec run --view native` under Xvfb (a real X server, in memory), read back from screenshots of the
screen (xwd): the window opens on the environment's camera; fullscreen fills the screen; auto_start false
holds the simulation until space is pressed in the window; the viewport mode draws wireframes; show_framerate
and show_debug draw their boxes, top right and bottom left."""

from __future__ import annotations

import os
import shutil
import struct
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from runtime_helpers import Morsec, scene, scene_file, wait_until

from morsec.runtime.x11 import press_in_own_windows

MORSEC = Path(sys.executable).with_name("morsec")

SCREEN = (800, 600)
CAMERA = {"location": [4.0, -4.0, 2.5], "rotation": [1.1, 0.0, 0.7854]}
SPACE = 0x20  # the X keysym of the space bar
SETTLE = 2.0  # wall-clock s for the window to draw what the view last synced


@pytest.fixture(scope="module")
def xvfb():
    """An Xvfb display of SCREEN's size, on a display number the server picks (-displayfd)."""
    if shutil.which("Xvfb") is None or shutil.which("xwd") is None:
        pytest.fail("Xvfb and xwd are needed: apt-get install xvfb x11-apps (.ci/run does)")
    read, write = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write), "-screen", "0", f"{SCREEN[0]}x{SCREEN[1]}x24",
                               "-nolisten", "tcp"], pass_fds=(write,), stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    os.close(write)
    with os.fdopen(read) as pipe:
        number = pipe.readline().strip()
    try:
        yield f":{number}"
    finally:
        server.terminate()
        server.wait(timeout=10)


def screenshot(display: str) -> np.ndarray:
    """The whole screen, RGB (xwd's ZPixmap of 24 or 32 bits a pixel)."""
    raw = subprocess.run(["xwd", "-root", "-silent", "-display", display], capture_output=True, check=True,
                         timeout=30).stdout
    header = struct.unpack(">25I", raw[:100])
    header_size, width, height, byte_order, bits, line, colours = (header[0], header[4], header[5], header[7],
                                                                   header[11], header[12], header[19])
    size = bits // 8
    start = header_size + colours * 12
    pixels = np.frombuffer(raw[start:start + line * height], np.uint8).reshape(height, line)[:, :width * size]
    pixels = pixels.reshape(height, width, size)
    rgb = [2, 1, 0] if byte_order == 0 else [size - 3, size - 2, size - 1]  # LSBFirst: B G R (X)
    return pixels[:, :, rgb].astype(int)


def sim_time(sim: Morsec) -> float:
    with sim.client() as client:
        return float(client.ok("time", "statistics")["simulated_time"])


def shoot(tmp_path: Path, display: str, monkeypatch, name: str, **environment):
    """Run a robot's scene in the native viewer; the screenshot once it has drawn, and the simulated time
    then and SETTLE later (still the same while paused)."""
    monkeypatch.setenv("DISPLAY", display)
    path = scene_file(tmp_path, scene(strategy="best_effort", environment={"camera": CAMERA, **environment}),
                      name=name)
    sim = Morsec(path, tmp_path, args=("--view", "native"))
    with sim:
        time.sleep(SETTLE)
        image = screenshot(display)
        before = sim_time(sim)
        time.sleep(SETTLE / 2)
        after = sim_time(sim)
        resumed = None
        if environment.get("auto_start") is False:
            assert press_in_own_windows(SPACE, pid=sim.pid)
            resumed = wait_until(lambda: (t := sim_time(sim)) > after + 0.2 and t, timeout=20)
    return image, (before, after, resumed), sim


def red(image: np.ndarray) -> np.ndarray:
    return (image[:, :, 0] > 120) & (image[:, :, 1] < 60) & (image[:, :, 2] < 60)


def edges(image: np.ndarray) -> float:
    right = np.abs(np.diff(image, axis=1)).sum(axis=2)[:-1, :]
    below = np.abs(np.diff(image, axis=0)).sum(axis=2)[:, :-1]
    return float(((right > 60) | (below > 60)).mean())


@pytest.fixture(scope="module")
def shots(xvfb, tmp_path_factory):
    """Three runs: the default window; fullscreen, paused, wireframe; the same with both overlays."""
    monkeypatch = pytest.MonkeyPatch()
    try:
        paused = {"fullscreen": True, "auto_start": False, "viewport": {"shade": "WIREFRAME"}}
        return {"plain": shoot(tmp_path_factory.mktemp("plain"), xvfb, monkeypatch, "plain"),
                "paused": shoot(tmp_path_factory.mktemp("paused"), xvfb, monkeypatch, "paused", **paused),
                "overlays": shoot(tmp_path_factory.mktemp("overlays"), xvfb, monkeypatch, "overlays", **paused,
                                  show_framerate=True, show_debug=True)}
    finally:
        monkeypatch.undo()


def test_the_window_opens_on_the_environments_camera(shots):
    image, (before, after, _), sim = shots["plain"]
    window = image.sum(axis=2) > 0  # the rest of the screen is Xvfb's black root window
    rows, cols = np.nonzero(window)
    width, height = cols.max() + 1 - cols.min(), rows.max() + 1 - rows.min()
    assert width < SCREEN[0] * 0.8 and height < SCREEN[1] * 0.8  # mujoco.viewer's window: 2/3 of the screen
    robot_rows, robot_cols = np.nonzero(red(image))
    assert len(robot_rows) > 200  # the robot, seen from the camera that looks at it, near the window's middle
    assert abs(robot_cols.mean() - (cols.min() + width / 2)) < width * 0.15
    assert after > before  # running
    assert "PAUSED" not in sim.output() and "display settings" not in sim.output()


def test_fullscreen_fills_the_screen_and_auto_start_false_waits_for_space(shots):
    image, (before, after, resumed), sim = shots["paused"]
    assert (image.sum(axis=2) == 0).mean() < 0.01  # no black root window left
    assert before == after == 0.0  # paused: no frame ran
    assert resumed is not None and resumed > 0.2  # space pressed in the window: running
    assert "PAUSED (auto_start is false): in the viewer, space runs it" in sim.output()


def test_the_viewport_mode_draws_wireframes(shots):
    """The floor, flat checkered patches when drawn whole, becomes a grid of lines on the sky's colour."""
    plain, paused = shots["plain"][0], shots["paused"][0]
    window = plain.sum(axis=2) > 0
    rows = np.nonzero(window.any(axis=1))[0]
    cols = np.nonzero(window.any(axis=0))[0]
    floor = plain[rows.min() + (rows.max() - rows.min()) * 3 // 4:rows.max(), cols.min():cols.max()]
    wire_floor = paused[SCREEN[1] * 3 // 4:SCREEN[1] - 40]
    assert edges(floor) < 0.005 and edges(wire_floor) > 0.015, (edges(floor), edges(wire_floor))  # measured 0, 0.026


def test_show_framerate_and_show_debug_draw_their_boxes(shots):
    """The same paused screen with and without the overlays: they differ in the top right corner (the frame
    rate) and the bottom left one (the debug rows), nowhere else."""
    without, with_overlays = shots["paused"][0], shots["overlays"][0]
    diff = np.abs(with_overlays - without).sum(axis=2) > 60
    w, h = SCREEN
    top_right = diff[:h // 6, w * 2 // 3:]
    bottom_left = diff[h * 5 // 6:, :w // 2]
    assert top_right.sum() > 200 and bottom_left.sum() > 200, (top_right.sum(), bottom_left.sum())
    assert diff.sum() - top_right.sum() - bottom_left.sum() < 0.1 * diff.sum()


def test_the_native_viewer_closes_cleanly(xvfb, tmp_path):
    """The viewer's render thread is waited for: without, the process died of a segmentation fault at exit
    about one run in two."""
    path = scene_file(tmp_path, scene())
    env = dict(os.environ, DISPLAY=xvfb)
    for _ in range(3):
        result = subprocess.run([str(MORSEC), "run", str(path), "--view", "native", "--duration", "1",
                                 "--service-port", "0", "--port-base", "0"], cwd=tmp_path, capture_output=True,
                                text=True, timeout=120, env=env)
        assert result.returncode == 0, result.stderr[-2000:]
