"""MORSE's PR2 variants on BasePR2's body (robots bare_pr2, localized_pr2, nav_pr2): builder scripts written as
MORSE's users wrote them, run by `morsec run` and driven over real sockets by morsec's pymorse client: NavPR2
drives sideways and forward, its odometry counts it and its base laser measures a wall coming closer;
LocalizedPR2's pose follows its motion; BarePR2 is the body alone. Their ROS interface is tested against
a real roscore in tests/test_ros.py."""

from __future__ import annotations

import math
import textwrap

import pytest
from runtime_helpers import Morsec

from morsec.app.convert import scene_source
from morsec.client import Morse
from morsec.compiler.urdf import expand_xacro
from morsec.component.catalogue import declaring_folder, load_catalogue
from morsec.frontends.load import load_scene
from morsec.testing import simulate

BASE_PR2 = {"pr2.torso", "pr2.torso.pose", "pr2.head", "pr2.head.pose", "pr2.l_arm", "pr2.l_arm.pose", "pr2.r_arm",
            "pr2.r_arm.pose", "pr2.joint_state", "pr2.posture"}
WALL_X, WALL_HALF = 3.0, 0.1  # the wall's centre and half thickness (a Blender cube scaled 0.1 along x)
LASER_X = 0.275  # NavPR2's base_scan, ahead of the robot's origin

NAV_SCRIPT = """
from morse.builder import *

pr2 = NavPR2()
pr2.add_interface('socket')
pr2.motion.add_stream('socket')
pr2.odometry.add_stream('socket')
pr2.base_scan.add_stream('socket')

wall = Cube('wall')
wall.scale = (0.1, 2.0, 1.0)
wall.translate(x=3.0, z=1.0)

env = Environment('empty', fastmode=True)
"""


def drive(sim, command: dict, seconds: float) -> None:
    """Publish a motion command for `seconds` of simulated time, then stop."""
    sim.pr2.motion.publish(command)
    sim.sleep(seconds)
    sim.pr2.motion.publish({"x": 0.0, "y": 0.0, "w": 0.0})
    sim.sleep(0.1)


def test_nav_pr2_drives_counts_and_scans_over_sockets(tmp_path):
    """NavPR2: BasePR2's components plus motion, keyboard, odometry and base_scan (MORSE's names); the laser
    gives 181 rays over 180 degrees, the one straight ahead measuring the wall from 0.275 m ahead of the
    origin; MotionXYW in MORSE's Position mode moves the base by speed x time, sideways as well as forward,
    which the odometry counts and the laser sees (the wall 1 m closer after 1 m forward)."""
    script = tmp_path / "nav_pr2.py"
    script.write_text(NAV_SCRIPT)
    with Morsec(script, tmp_path, prebuild=False, strategy="fixed_step") as server, \
            Morse("localhost", server.service_port) as sim:
        details = server.client().ok("simulation", "details")
        assert set(details["robots"][0]["components"]) == BASE_PR2 | {
            "pr2.motion", "pr2.keyboard", "pr2.odometry", "pr2.base_scan"}
        assert set(server.streams) == {"pr2.joint_state", "pr2.posture", "pr2.motion", "pr2.odometry",
                                       "pr2.base_scan"}

        scan = sim.pr2.base_scan.get()
        ahead = WALL_X - WALL_HALF - LASER_X
        assert len(scan["range_list"]) == 181
        assert scan["range_list"][90] == pytest.approx(ahead, abs=0.01)
        assert scan["range_list"][0] == pytest.approx(30.0)  # to the right: nothing within its 30 m
        assert scan["range_list"][90 - 30] == pytest.approx(ahead / math.cos(math.radians(30)), abs=0.01)

        drive(sim, {"x": 0.0, "y": 0.5, "w": 0.0}, 1.0)
        odometry = sim.pr2.odometry.get()
        assert (odometry["x"], odometry["y"]) == (pytest.approx(0.0, abs=0.01), pytest.approx(0.5, abs=0.02))

        drive(sim, {"x": 0.5, "y": 0.0, "w": 0.0}, 2.0)
        odometry = sim.pr2.odometry.get()
        assert (odometry["x"], odometry["y"]) == (pytest.approx(1.0, abs=0.02), pytest.approx(0.5, abs=0.02))
        assert odometry["yaw"] == pytest.approx(0.0, abs=0.01)
        assert sim.pr2.base_scan.get()["range_list"][90] == pytest.approx(ahead - odometry["x"], abs=0.01)

        drive(sim, {"x": 0.0, "y": 0.0, "w": 0.5}, 1.0)
        assert sim.pr2.odometry.get()["yaw"] == pytest.approx(0.5, abs=0.02)
        assert sim.pr2.joint_state.get()["torso_lift_joint"] == pytest.approx(0.0, abs=1e-3)  # BasePR2's still


LOCALIZED_SCRIPT = """
from morse.builder import *

pr2 = LocalizedPR2(with_keyboard=False)
pr2.translate(x=1.0, y=-2.0)
pr2.add_interface('socket')
pr2.motion.add_stream('socket')
pr2.pose.add_stream('socket')

env = Environment('empty', fastmode=True)
"""


def test_localized_pr2_knows_where_it_drives_over_sockets(tmp_path):
    """LocalizedPR2(with_keyboard=False): BasePR2's components plus motion and pose, no keyboard; the pose
    reads where the robot stands (its origin on the floor) and follows its motion, forward in its heading."""
    script = tmp_path / "localized_pr2.py"
    script.write_text(LOCALIZED_SCRIPT)
    with Morsec(script, tmp_path, prebuild=False, strategy="fixed_step") as server, \
            Morse("localhost", server.service_port) as sim:
        details = server.client().ok("simulation", "details")
        assert set(details["robots"][0]["components"]) == BASE_PR2 | {"pr2.motion", "pr2.pose"}
        pose = sim.pr2.pose.get()
        assert (pose["x"], pose["y"], pose["z"]) == (pytest.approx(1.0, abs=0.01), pytest.approx(-2.0, abs=0.01),
                                                     pytest.approx(0.0, abs=0.01))
        drive(sim, {"x": 0.0, "y": 0.0, "w": math.pi / 4}, 2.0)  # a quarter turn: facing +y
        drive(sim, {"x": 0.5, "y": 0.0, "w": 0.0}, 2.0)
        pose = sim.pr2.pose.get()
        assert pose["yaw"] == pytest.approx(math.pi / 2, abs=0.03)
        assert (pose["x"], pose["y"]) == (pytest.approx(1.0, abs=0.03), pytest.approx(-1.0, abs=0.03))


BARE_YAML = """
environment: {name: empty, time: {strategy: fixed_step}}
robots:
  - {name: bare, type: BarePR2, translate: [0.0, 0.0, 0.0]}
  - {name: base, type: BasePR2, translate: [3.0, 0.0, 0.0]}
"""


def test_bare_pr2_is_base_pr2s_body_alone(tmp_path):
    """BarePR2: no components, the same body as BasePR2 (the one xacro file, read from pr2's folder), standing
    on the floor as BasePR2 does."""
    cat = load_catalogue()
    bare, base = cat.get("robots", "BarePR2"), cat.get("robots", "BasePR2")
    assert declaring_folder(bare, "xacro") == base.folder and not (bare.folder / bare.xacro).exists()
    assert expand_xacro(declaring_folder(bare, "xacro") / bare.xacro, {"name": "pr2"}) == \
        expand_xacro(base.folder / base.xacro, {"name": "pr2"})
    with simulate(BARE_YAML, tmp_path) as sim:
        sim.run_for(0.5)
        assert sim.sim.scene["robots"][0]["components"] == []
        (bare_at, bare_rot), (base_at, _) = sim.body_pose("bare"), sim.body_pose("base")
        assert bare_at == pytest.approx([0.0, 0.0, 0.0], abs=2e-3) and bare_rot[2, 2] == pytest.approx(1.0, abs=1e-4)
        assert bare_at[2] == pytest.approx(base_at[2], abs=1e-4)


VARIANTS_YAML = """
environment: {name: empty}
robots:
  - {name: nav, type: NavPR2, without: [keyboard, posture]}
  - {name: located, type: localized_pr2, translate: [0.0, 3.0, 0.0]}
"""


def test_a_yaml_scene_names_the_variants_and_leaves_components_out(tmp_path):
    """In YAML the variants come with their components as MORSE's classes built them; `without` leaves some
    out (what NavPR2(with_keyboard=False) writes); NavPR2(show_laser=True) shows the laser's arc."""
    with simulate(VARIANTS_YAML, tmp_path) as sim:
        nav, located = sim.sim.scene["robots"]
        assert [c["name"] for c in nav["components"]] == ["torso", "head", "l_arm", "r_arm", "joint_state", "motion",
                                                          "odometry", "base_scan"]
        motion = next(c for c in nav["components"] if c["name"] == "motion")
        assert motion["type"] == "motion_xyw" and motion["properties"]["ControlType"] == "Position"
        scan = next(c for c in nav["components"] if c["name"] == "base_scan")
        assert scan["translate"] == [0.275, 0.0, 0.252] and scan["properties"]["scan_window"] == 180.0
        assert [c["name"] for c in located["components"]][-3:] == ["motion", "keyboard", "pose"]
        assert "nav.keyboard" not in sim.sim.by_name and "located.keyboard" in sim.sim.by_name


def test_morse_builder_arguments_of_the_variants(tmp_path):
    """NavPR2(name, with_keyboard=False, show_laser=True), as MORSE's: named, no keyboard (`without` in the
    scene), the laser's arc shown; LocalizedPR2 takes the same arguments; BarePR2 only a name."""
    script = tmp_path / "arguments.py"
    script.write_text(textwrap.dedent("""
        from morse.builder import *
        from morse.builder.robots import NavPR2, LocalizedPR2, BarePR2

        nav = NavPR2("navigator", with_keyboard=False, show_laser=True)
        located = LocalizedPR2(with_keyboard=True, show_laser=True)
        located.translate(y=3.0)
        bare = BarePR2("bare")
        bare.translate(y=-3.0)
        env = Environment('empty')
    """))
    data, _ = scene_source(script, load_catalogue())
    nav, located, bare = data["robots"]
    assert (nav["name"], nav["without"]) == ("navigator", ["keyboard"])
    assert "keyboard" not in [c["name"] for c in nav["components"]]
    assert next(c for c in nav["components"] if c["name"] == "base_scan")["properties"]["Visible_arc"] is True
    assert "without" not in located and "keyboard" in [c["name"] for c in located["components"]]
    assert (bare["name"], bare.get("components", [])) == ("bare", [])
    scene = load_scene(script)
    assert [r.name for r in scene.robots] == ["navigator", "located", "bare"]
    assert "keyboard" not in [c.name for c in scene.robots[0].components]  # not added back as a default
