"""ptu and ptu_posture: real pan and tilt joints moved at Speed within Tolerance, look_at_point /
look_at_object aim the tilt body's x axis, a camera appended to the unit rides on the tilt body."""

from __future__ import annotations

import math
from pathlib import Path

import mujoco
import numpy as np
import pytest

from morsec.errors import SceneError
from morsec.testing import simulate

SCENES = Path(__file__).resolve().parents[2] / "scenes"


def scene(speed: float = 1.0, manual: bool = False, camera: bool = True) -> str:
    cam = "          - {name: camera, type: video_camera, translate: [0.03, 0.0, 0.04], frequency: 2,\n" \
          "             properties: {cam_width: 64, cam_height: 48}}\n" if camera else ""
    return f"""
robots:
  - name: robot
    type: fake_robot
    translate: [0.0, 0.0, 1.0]
    components:
      - name: ptu
        type: ptu
        services: [socket]
        properties: {{Speed: {speed}, Manual: {str(manual).lower()}}}
        components:
{cam}          - {{name: posture, type: ptu_posture}}
objects:
  - {{name: crate, type: box, translate: [2.0, -1.0, 0.25], properties: {{Label: crate}}}}
"""


@pytest.mark.parametrize("speed", [1.0, 2.0])
def test_set_pan_tilt_reaches_the_angles_at_the_speed(speed, tmp_path):
    with simulate(scene(speed, camera=False), tmp_path) as sim:
        client = sim.client()
        start = sim.time
        rid = client.send("robot.ptu", "set_pan_tilt", 1.2, -0.6)
        sim.run_for(0.5)
        pan, tilt = sim.call("robot.ptu", "get_pan_tilt")
        assert pan == pytest.approx(min(1.2, 0.5 * speed), abs=0.03)  # moving at Speed, tilt too
        assert tilt == pytest.approx(-min(0.6, 0.5 * speed), abs=0.03)
        status, _, at = client.wait(rid)
        assert status == "SUCCESS"
        assert at - start == pytest.approx(1.2 / speed, abs=0.06)  # the longer axis, at Speed
        pan, tilt = sim.call("robot.ptu", "get_pan_tilt")
        tolerance = math.radians(0.3)
        assert abs(pan - 1.2) < tolerance and abs(tilt + 0.6) < tolerance
        sim.step()
        posture = sim.data("robot.ptu.posture")
        assert posture["pan"] == pytest.approx(pan, abs=1e-3) and posture["tilt"] == pytest.approx(tilt, abs=1e-3)


def test_look_at_point_aims_the_tilt_body_and_the_camera_turns_with_it(tmp_path):
    """The tilt body's x axis turns parallel to the direction from the unit's origin to the point (MORSE's
    aim; ptu_testing: look_at_point(1, 0, z of the unit) gives a tilt of 0)."""
    with simulate(scene(), tmp_path) as sim:
        model = sim.sim.model
        tilt = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "robot.ptu/tilt")
        camera = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "robot.ptu.camera")
        assert model.body_parentid[camera] == tilt  # appended to the unit: nested in its tilt body

        client = sim.client()
        point = np.array([1.0, 2.0, 0.2])
        status, _, _ = client.wait(client.send("robot.ptu", "look_at_point", *point))
        assert status == "SUCCESS"
        sim.run_for(0.2)
        pos, rot = sim.body_pose("robot.ptu/tilt")
        origin, _ = sim.body_pose("robot.ptu")  # MORSE aims from the unit's origin, not from the tilt axis
        aim = (point - origin) / np.linalg.norm(point - origin)
        assert math.degrees(math.acos(min(1.0, float(rot[:, 0] @ aim)))) < 0.5
        pan, tilt_angle = sim.call("robot.ptu", "get_pan_tilt")
        assert pan == pytest.approx(math.atan2(2.0, 1.0), abs=0.01)  # left
        assert tilt_angle > 0  # the point is below the unit: it looks down

        cam_pos, cam_rot = sim.body_pose("robot.ptu.camera")
        np.testing.assert_allclose(cam_rot, rot, atol=1e-9)  # the camera's frame turned with the tilt body
        np.testing.assert_allclose(cam_pos, pos + rot @ [0.03, 0.0, 0.04], atol=1e-9)
        # the MuJoCo camera that renders the pictures looks where the camera's +x looks
        cam = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, "robot.ptu.camera")
        mujoco.mj_camlight(model, sim.sim.data)
        view = -sim.sim.data.cam_xmat[cam].reshape(3, 3)[:, 2]
        np.testing.assert_allclose(view, rot[:, 0], atol=1e-9)


def test_a_point_at_the_height_of_the_unit_is_looked_at_level(tmp_path):
    """MORSE's ptu_testing: look_at_point at the unit's own height gives a tilt of 0 (the tilt axis is 0.09 m
    above the unit's origin, which MORSE aimed from)."""
    with simulate(scene(camera=False), tmp_path) as sim:
        client = sim.client()
        origin, _ = sim.body_pose("robot.ptu")
        status, _, _ = client.wait(client.send("robot.ptu", "look_at_point", origin[0] + 1.0, origin[1], origin[2]))
        assert status == "SUCCESS"
        pan, tilt = sim.call("robot.ptu", "get_pan_tilt")
        assert abs(pan) < 0.01 and abs(tilt) < 0.01


def test_look_at_object_and_unknown_objects(tmp_path):
    with simulate(scene(camera=False), tmp_path) as sim:
        client = sim.client()
        status, _, _ = client.wait(client.send("robot.ptu", "look_at_object", "crate"))
        assert status == "SUCCESS"
        pos, rot = sim.body_pose("robot.ptu")
        _, rot = sim.body_pose("robot.ptu/tilt")
        aim = np.array([2.0, -1.0, 0.25]) - pos
        assert math.degrees(math.acos(min(1.0, float(rot[:, 0] @ aim / np.linalg.norm(aim))))) < 0.5
        status, message, _ = client.wait(client.send("robot.ptu", "look_at_object", "crat"))
        assert status == "FAILED" and "crate" in message  # did you mean


def test_cancel_stops_where_it_is_and_a_new_target_preempts(tmp_path):
    with simulate(scene(camera=False), tmp_path) as sim:
        client = sim.client()
        first = client.send("robot.ptu", "set_pan_tilt", 2.0, 0.0)
        sim.run_for(0.5)
        second = client.send("robot.ptu", "set_pan_tilt", -0.3, 0.2)
        sim.step()  # an asynchronous service starts with the end of the next frame (MORSE's frame order)
        assert client.replies[first][0] == "PREEMPTED"
        sim.run_for(0.3)
        client.cancel(second)
        assert client.replies[second][0] == "PREEMPTED"
        stopped = sim.call("robot.ptu", "get_pan_tilt")
        sim.run_for(0.5)
        np.testing.assert_allclose(sim.call("robot.ptu", "get_pan_tilt"), stopped, atol=0.01)


def test_streamed_fields_move_the_unit_unless_manual(tmp_path):
    with simulate(scene(camera=False), tmp_path) as sim:
        sim.command("robot.ptu", pan=-0.4, tilt=0.3)
        sim.run_for(0.6)
        assert sim.call("robot.ptu", "get_pan_tilt") == pytest.approx([-0.4, 0.3], abs=0.01)
    (tmp_path / "manual").mkdir()
    with simulate(scene(manual=True, camera=False), tmp_path / "manual") as sim:
        sim.command("robot.ptu", pan=-0.4, tilt=0.3)
        sim.run_for(0.6)
        assert sim.call("robot.ptu", "get_pan_tilt") == pytest.approx([0.0, 0.0], abs=0.01)


def test_a_mount_body_missing_from_the_model_is_a_scene_error(tmp_path):
    folder = tmp_path / "project" / "components" / "actuators" / "bad_mount"
    folder.mkdir(parents=True)
    (tmp_path / "project" / "morsec.toml").write_text('[project]\nname = "p"\ncomponents = ["components"]\n')
    (folder / "component.py").write_text(
        "from morsec.component import Actuator\n\n\nclass BadMount(Actuator):\n"
        "    \"\"\"Mounts its children on a body it does not have.\"\"\"\n    mount_body = \"nope\"\n\n\n"
        "COMPONENT = BadMount\n")
    text = ("robots:\n  - name: r\n    type: fake_robot\n    components:\n      - name: m\n        type: bad_mount\n"
            "        components: [{name: p, type: pose}]\n")
    with pytest.raises(SceneError, match=r"'r\.m'.*'r\.m/nope'"):
        with simulate(text, tmp_path, project=tmp_path / "project"):
            pass


def test_ptu_camera_scene_looks_at_the_red_box(tmp_path):
    """The example scene: once the unit looks at the red box, the middle of the camera's picture is red."""
    with simulate((SCENES / "ptu_camera.yaml").read_text(), tmp_path) as sim:
        client = sim.client()
        status, _, _ = client.wait(client.send("robot.ptu", "look_at_object", "red_box"))
        assert status == "SUCCESS"
        sim.run_for(0.2)
        image = sim.data("robot.ptu.camera")["image"]
        h, w = image.shape[:2]
        r, g, b = (float(v) for v in image[h // 2 - 4:h // 2 + 4, w // 2 - 4:w // 2 + 4, :3].reshape(-1, 3).mean(0))
        assert r > 60 and r > 2 * g and r > 2 * b  # the box's red (0.8, 0.1, 0.1), in the shade or not
        posture = sim.data("robot.ptu.posture")
        assert posture["pan"] == pytest.approx(sim.call("robot.ptu", "get_pan_tilt")[0], abs=0.02)
