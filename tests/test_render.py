"""`morsec render`: a picture of the scene, headless on the CPU, from the environment's camera."""

import subprocess
import sys

import numpy as np
import pytest

from morsec.kits.png import read_png, write_png

SCENE = """
environment:
  name: empty
  camera: {location: [4.0, -4.0, 2.5], rotation: [1.1, 0.0, 0.7854]}
robots:
  - {name: robot, type: atrv}
"""


def morsec(*args, cwd):
    return subprocess.run([sys.executable, "-m", "morsec", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=120)


def test_png_round_trip(tmp_path):
    image = np.random.default_rng(0).integers(0, 255, (7, 5, 3), dtype=np.uint8)
    write_png(tmp_path / "x.png", image)
    assert (read_png(tmp_path / "x.png") == image).all()


def test_render_shows_the_robot(tmp_path):
    """The robot's pixels differ from the background: the same view without the robot is the reference."""
    (tmp_path / "with.yaml").write_text(SCENE)
    (tmp_path / "without.yaml").write_text(SCENE.split("robots:")[0])
    for name in ("with", "without"):
        result = morsec("render", f"{name}.yaml", "-o", f"{name}.png", "--width", "320", "--height", "240",
                        cwd=tmp_path)
        assert result.returncode == 0, result.stderr
    with_robot = read_png(tmp_path / "with.png").astype(int)
    background = read_png(tmp_path / "without.png").astype(int)
    assert with_robot.shape == (240, 320, 3)
    assert with_robot.std() > 10  # not blank
    changed = np.abs(with_robot - background).sum(axis=2) > 60
    assert changed.sum() > 200  # the robot covers a visible patch ...
    rows, cols = np.nonzero(changed)
    assert 60 < rows.mean() < 200 and 80 < cols.mean() < 260  # ... near the centre, where the camera aims
    red = with_robot[changed]
    assert (red[:, 0] > red[:, 2] + 30).mean() > 0.3  # the ATRV is red


def test_render_errors_are_one_line(tmp_path):
    (tmp_path / "s.yaml").write_text(SCENE)
    result = morsec("render", "s.yaml", "-o", "x.png", "--camera", "nope", cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.strip().splitlines() == ["error: no camera 'nope' in the scene; cameras: morsec_default"]


def edges(image: np.ndarray) -> np.ndarray:
    """Pixels where the colour jumps (sum of |RGB| differences > 60) to the right or below neighbour."""
    right = np.abs(np.diff(image, axis=1)).sum(axis=2)[:-1, :]
    below = np.abs(np.diff(image, axis=0)).sum(axis=2)[:, :-1]
    return (right > 60) | (below > 60)


@pytest.mark.parametrize("shade", ["WIREFRAME"])
def test_render_uses_the_viewport_setting(tmp_path, shade):
    """In wireframe the checkered floor becomes a grid of lines over the background: most of the picture
    changes colour, and the floor, flat patches of two colours when solid, is crossed by many edges."""
    (tmp_path / "solid.yaml").write_text(SCENE)
    (tmp_path / "wire.yaml").write_text(SCENE.replace("name: empty", f"name: empty\n  viewport: {{shade: {shade}}}"))
    for name in ("solid", "wire"):
        result = morsec("render", f"{name}.yaml", "-o", f"{name}.png", "--width", "160", "--height", "120",
                        cwd=tmp_path)
        assert result.returncode == 0, result.stderr
    solid = read_png(tmp_path / "solid.png").astype(int)
    wire = read_png(tmp_path / "wire.png").astype(int)
    changed = np.abs(solid - wire).sum(axis=2) > 60
    assert changed.mean() > 0.3, f"only {changed.mean():.1%} of the pixels changed"
    floor = slice(70, 120)  # the lower rows: ground only (the robot is in rows 44-58, the horizon above)
    solid_edges, wire_edges = edges(solid[floor]).mean(), edges(wire[floor]).mean()
    assert solid_edges < 0.02 and wire_edges > 0.06, (solid_edges, wire_edges)  # measured: 0.0 and 0.12
