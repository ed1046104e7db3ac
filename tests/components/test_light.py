"""light (a MuJoCo spot light switched through model.light_active: a camera sees the difference) and
arucomarker (a marker moved to the pose of its fields, MORSE's axis conversion)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from morsec.testing import simulate


def light_scene(props: str = "{}") -> str:
    # the lamp and a camera side by side, both facing a grey wall lit from the side by nothing else
    return f"""
robots:
  - name: robot
    type: fake_robot
    translate: [0.0, 0.0, 0.5]
    components:
      - {{name: lamp, type: light, services: [socket], properties: {props}}}
      - {{name: camera, type: video_camera, translate: [0.0, 0.0, 0.1], frequency: 60,
         properties: {{cam_width: 64, cam_height: 48}}}}
objects:
  - {{name: wall, type: box, translate: [2.0, 0.0, 0.5], size: [0.2, 3.0, 1.0], color: [0.5, 0.5, 0.5]}}
"""


def brightness(sim) -> float:
    sim.step()
    return float(sim.data("robot.camera")["image"][16:32, 24:40, :3].astype(float).mean())


def test_light_toggles_and_the_camera_sees_it(tmp_path):
    with simulate(light_scene(), tmp_path) as sim:
        light = mujoco.mj_name2id(sim.sim.model, mujoco.mjtObj.mjOBJ_LIGHT, "robot.lamp")
        assert sim.sim.model.light_active[light] and sim.data("robot.lamp")["emit"] is True
        on = brightness(sim)
        assert sim.call("robot.lamp", "toggle") is True
        assert not sim.sim.model.light_active[light] and sim.data("robot.lamp")["emit"] is False
        off = brightness(sim)
        assert on > off + 50  # the spot lights the wall
        sim.call("robot.lamp", "toggle", False)  # an explicit value sets, it does not toggle
        assert brightness(sim) == pytest.approx(off)
        sim.call("robot.lamp", "toggle", True)
        assert brightness(sim) == pytest.approx(on)
        sim.command("robot.lamp", emit=False)  # the stream's field
        assert brightness(sim) == pytest.approx(off)


def test_a_lit_green_box_shows_its_own_green(tmp_path):
    """MORSE's light_testing: a camera facing MORSE's GreenBox (0, 0.952, 0.019) from 1.3 m sees no bright
    green without the lamp, and with it most of the face in pure green (R < 10, G > 170, B < 30): pictures
    have no camera-following highlight (MuJoCo's headlight has no specular part, as Blender had none)."""
    text = light_scene().replace(
        "{name: wall, type: box, translate: [2.0, 0.0, 0.5], size: [0.2, 3.0, 1.0], color: [0.5, 0.5, 0.5]}",
        "{name: block, type: box, translate: [1.8, 0.0, 0.6], size: [1.0, 1.0, 1.8], color: [0.0, 0.952, 0.019]}")
    assert "block" in text

    def green(sim) -> int:
        sim.step()
        img = sim.data("robot.camera")["image"].astype(int)
        return int(((img[..., 0] < 10) & (img[..., 1] > 170) & (img[..., 2] < 30)).sum())

    with simulate(text, tmp_path) as sim:
        lit = green(sim)
        sim.call("robot.lamp", "toggle", False)
        assert green(sim) == 0
    assert lit > 0.5 * 64 * 48  # the face fills most of the picture


def test_light_properties_in_the_mjcf(tmp_path):
    props = "{emit: false, distance: 4.0, color: '(1, 0.5, 0)', size: 1.0, energy: 0.8}"
    with simulate(light_scene(props), tmp_path) as sim:
        m = sim.sim.model
        light = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_LIGHT, "robot.lamp")
        assert not m.light_active[light] and sim.data("robot.lamp")["emit"] is False  # starts off
        assert m.light_cutoff[light] == pytest.approx(math.degrees(0.5))  # size: the cone's full angle
        np.testing.assert_allclose(m.light_attenuation[light], [1.0, 0.0, 1 / 16])  # half at 4 m
        np.testing.assert_allclose(m.light_diffuse[light], [0.8, 0.4, 0.0])  # colour x energy


def test_light_colour_is_checked(tmp_path):
    from morsec.errors import SceneError
    with pytest.raises(SceneError, match="color"):
        with simulate(light_scene("{color: 'red'}"), tmp_path):
            pass


def marker_scene(props: str = "{}", rotate: str = "[0.0, 0.0, 0.0]") -> str:
    return f"""
robots:
  - name: robot
    type: fake_robot
    translate: [1.0, 2.0, 0.5]
    rotate: {rotate}
    components:
      - {{name: aruco, type: arucomarker, translate: [0.6, 0.1, 0.2], properties: {props}}}
"""


def test_arucomarker_starts_where_the_scene_put_it(tmp_path):
    with simulate(marker_scene("{xoffset: 0.1, zoffset: 0.3}"), tmp_path) as sim:
        before = sim.component("robot.aruco").position().copy()
        data = sim.data("robot.aruco")
        # ArUco axes: z forward = robot x - xoffset, x right... = robot y - yoffset, y down = zoffset - robot z
        assert (data["z"], data["x"], data["y"]) == pytest.approx((0.5, 0.1, 0.1))
        sim.run_for(0.2)
        np.testing.assert_allclose(sim.component("robot.aruco").position(), before, atol=1e-9)


def test_arucomarker_goes_to_the_pose_of_its_fields(tmp_path):
    with simulate(marker_scene("{xoffset: -0.09, zoffset: 0.3}", rotate="[0.0, 0.0, 1.5707963]"), tmp_path) as sim:
        sim.command("robot.aruco", x=0.05, y=-0.02, z=1.2, roll=0.3, pitch=-0.2, yaw=0.5)
        sim.step()
        pos, rot = sim.body_pose("robot.aruco")
        base_pos, base_rot = sim.body_pose("robot")
        # robot frame: (z + xoffset, x + yoffset, -y + zoffset)
        np.testing.assert_allclose(base_rot.T @ (pos - base_pos), [1.2 - 0.09, 0.05, 0.02 + 0.3], atol=1e-9)

        def rx(a):
            return np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])

        def ry(a):
            return np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]])

        def rz(a):
            return np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])

        # Blender Euler order YZX: pitch first, then yaw, then roll
        np.testing.assert_allclose(base_rot.T @ rot, rx(0.3) @ rz(0.5) @ ry(-0.2), atol=1e-9)
        assert sim.call("robot.aruco", "get_world_position") == pytest.approx(list(pos))
        np.testing.assert_allclose(sim.call("robot.aruco", "get_local_orientation"), base_rot.T @ rot, atol=1e-9)


def test_arucomarker_pattern_is_black_and_white(tmp_path):
    with simulate(marker_scene(), tmp_path) as sim:
        m = sim.sim.model
        body = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "robot.aruco")
        colours = {tuple(m.geom_rgba[g]) for g in np.flatnonzero(m.geom_bodyid == body)}
        assert colours == {(1.0, 1.0, 1.0, 1.0), (0.0, 0.0, 0.0, 1.0)}
        black = sum(1 for g in np.flatnonzero(m.geom_bodyid == body) if m.geom_rgba[g][0] == 0)
        assert black == 20 + 8  # the 6 x 6 grid's border (20 cells) and the 8 black cells of its 4 x 4 code
