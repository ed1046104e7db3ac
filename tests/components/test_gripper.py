"""gripper: grabs the nearest Graspable object in its cone (a MuJoCo weld, switched on at grab time), the
object follows it while held and falls where it is released."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from morsec.testing import simulate

BOX = 0.1  # m, the boxes' side


def scene(objects: str, gripper_props: str = "{}", height: float = 0.3) -> str:
    """A fixed (static) holder `height` up with a gripper pointing down (+x of the gripper along -z)."""
    return f"""
robots:
  - name: robot
    type: fake_robot
    translate: [0.0, 0.0, {height}]
    components:
      - {{name: gripper, type: gripper, rotate: [0.0, 1.5707963, 0.0], properties: {gripper_props}}}
objects:
{objects}
"""


def box(name: str, x: float, y: float = 0.0, z: float = BOX / 2, graspable: bool = True, dynamic: bool = True) -> str:
    props = "{Graspable: true}" if graspable else "{}"
    return (f"  - {{name: {name}, type: box, translate: [{x}, {y}, {z}], size: [{BOX}, {BOX}, {BOX}], "
            f"dynamic: {str(dynamic).lower()}, mass: 0.5, properties: {props}}}\n")


def move_robot(sim, delta, seconds: float) -> None:
    """Carry the robot along `delta` (m) in `seconds`, a little every frame, then let things settle."""
    robot = sim.sim.robots[0].handle
    frames = int(seconds * sim.sim.clock.frequency)
    for _ in range(frames):
        pos, rot = robot.pose()
        robot.set_pose(pos + np.asarray(delta) / frames, rot)
        sim.step()


def test_pick_move_release_the_box_falls_where_released(tmp_path):
    with simulate(scene(box("box", 0.0) + box("other", 0.4)), tmp_path) as sim:
        sim.run_for(0.3)
        gripper = sim.component("robot.gripper")
        assert sim.call("robot.gripper", "grab") == "box"  # right below (0.15 m), the other is off the cone
        assert sim.data("robot.gripper")["grab"] is True
        offset = sim.body_pose("box")[0] - gripper.position()

        move_robot(sim, [1.0, 0.5, 0.4], 2.0)  # up and away
        sim.run_for(0.5)
        held, rot = sim.body_pose("box")
        np.testing.assert_allclose(held - gripper.position(), offset, atol=0.005)  # it followed
        assert held[2] == pytest.approx(BOX / 2 + 0.4, abs=0.01)  # lifted off the ground
        assert abs(rot[2, 2]) > 0.99  # and not tipped over

        assert sim.call("robot.gripper", "release") is True
        assert sim.call("robot.gripper", "release") is False  # nothing held any more
        sim.run_for(1.0)
        landed, _ = sim.body_pose("box")
        assert landed[2] == pytest.approx(BOX / 2, abs=0.005)  # fell to the ground...
        np.testing.assert_allclose(landed[:2], held[:2], atol=0.01)  # ...straight down from where it was released
        np.testing.assert_allclose(sim.body_pose("other")[0][:2], [0.4, 0.0], atol=1e-3)  # left alone


def test_a_held_object_goes_along_when_the_robot_is_teleported(tmp_path):
    """MORSE's gripper_testing teleports the robot holding a tape: the object, parented to the gripper in MORSE,
    goes along; here it is put back in the hand (a weld pulling it across 5 m in one step blew the physics up)."""
    text = f"""
environment: {{name: empty, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: robot
    type: atrv
    components:
      - {{name: gripper, type: gripper, translate: [0.7, 0.0, 0.3], rotate: [0.0, 1.5707963, 0.0]}}
      - {{name: teleport, type: teleport}}
objects:
{box("box", 0.7)}"""
    with simulate(text, tmp_path) as sim:
        sim.run_for(0.3)
        gripper = sim.component("robot.gripper")
        assert sim.call("robot.gripper", "grab") == "box"
        offset = sim.body_pose("box")[0] - gripper.position()
        sim.command("robot.teleport", x=3.0, y=-4.0, z=0.5, yaw=0.0, pitch=0.0, roll=0.0)  # 5 m away, held up
        for _ in range(30):  # in the hand at once, and held there
            sim.step()
            np.testing.assert_allclose(sim.body_pose("robot")[0][:2], [3.0, -4.0], atol=0.01)
            np.testing.assert_allclose(sim.body_pose("box")[0] - gripper.position(), offset, atol=0.01)
        assert sim.call("robot.gripper", "release") is True
        sim.run_for(1.0)
        np.testing.assert_allclose(sim.body_pose("box")[0], [3.7, -4.0, BOX / 2], atol=0.02)  # fell below


def test_only_graspable_objects_in_the_cone_and_in_range_are_grabbed(tmp_path):
    objects = (box("plain", 0.0, graspable=False)  # right below, but not Graspable
               + box("aside", 0.0, 0.3)  # 0.32 m away, but 50 degrees off the gripper's axis (cone: 30)
               + box("far", 3.0))
    with simulate(scene(objects), tmp_path) as sim:
        sim.run_for(0.1)
        assert sim.call("robot.gripper", "grab") is None
        assert sim.data("robot.gripper")["grab"] is False
    (tmp_path / "wide").mkdir()
    with simulate(scene(objects, "{Angle: 115.0}"), tmp_path / "wide") as sim:  # a 115 degree cone sees it
        assert sim.call("robot.gripper", "grab") == "aside"
    (tmp_path / "range").mkdir()
    with simulate(scene(box("low", 0.0), height=0.7), tmp_path / "range") as sim:  # top 0.6 m below
        assert sim.component("robot.gripper").in_reach() == []
        sim.component("robot.gripper").properties.Distance = 0.65
        assert sim.call("robot.gripper", "grab") == "low"


def test_the_nearest_object_in_the_cone_is_grabbed(tmp_path):
    # the cone (60 degrees) from 0.3 m up reaches the ground 0.17 m around; two boxes, the nearer is taken
    objects = box("near", 0.02) + box("nearer", -0.03, z=BOX / 2 + 0.1)
    with simulate(scene(objects), tmp_path) as sim:
        reach = sim.component("robot.gripper").in_reach()
        assert [name for _, name in reach] == ["nearer", "near"]
        assert sim.call("robot.gripper", "grab") == "nearer"
        assert sim.call("robot.gripper", "grab") == "nearer"  # already holding it


def test_grab_field_streamed_in_grabs_and_releases(tmp_path):
    with simulate(scene(box("box", 0.0)), tmp_path) as sim:
        sim.command("robot.gripper", grab=True)
        sim.step()
        move_robot(sim, [0.0, 0.0, 0.3], 0.5)
        sim.run_for(0.3)
        assert sim.body_pose("box")[0][2] > 0.3
        sim.command("robot.gripper", grab=False)
        sim.run_for(1.0)
        assert sim.body_pose("box")[0][2] == pytest.approx(BOX / 2, abs=0.005)


def test_a_static_graspable_object_is_carried_kinematically(tmp_path):
    with simulate(scene(box("lid", 0.0, z=0.1, dynamic=False)), tmp_path) as sim:
        assert sim.call("robot.gripper", "grab") == "lid"
        move_robot(sim, [0.5, 0.0, 0.0], 0.5)
        np.testing.assert_allclose(sim.body_pose("lid")[0], [0.5, 0.0, 0.1], atol=1e-6)
        sim.call("robot.gripper", "release")
        move_robot(sim, [0.5, 0.0, 0.0], 0.5)
        np.testing.assert_allclose(sim.body_pose("lid")[0], [0.5, 0.0, 0.1], atol=1e-6)  # stays where left


def test_a_weld_per_dynamic_graspable_object_off_until_grab(tmp_path):
    with simulate(scene(box("a", 0.0) + box("b", 1.0) + box("c", 2.0, graspable=False)
                        + box("d", 3.0, dynamic=False)), tmp_path) as sim:
        model = sim.sim.model
        welds = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_EQUALITY, i) for i in range(model.neq)]
        assert welds == ["robot.gripper/a", "robot.gripper/b"]
        assert not model.eq_active0.any() and not sim.sim.data.eq_active.any()
        assert sim.component("robot.gripper").properties.Angle == 60.0  # degrees, as MORSE
