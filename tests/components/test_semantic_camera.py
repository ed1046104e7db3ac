"""semantic_camera in running simulations: which tagged objects it reports (in view, not hidden, not
outside the field of view), with which names and poses, world or relative — all computable by hand.
The default camera (256 x 256, 35 mm) sees tan(half angle) = 16 / 35 = 0.457 on each side."""

from __future__ import annotations

import json
import math

import mujoco
import pytest

from morsec.middleware.socket_streams import encode
from morsec.testing import simulate

HALF = 16 / 35  # tangent of the half field of view, both ways


def scene(objects: list[str], camera: str = "{name: sem, type: semantic_camera}", rotate=(0.0, 0.0, 0.0),
          at=(0.0, 0.0, 1.0)) -> str:
    objs = "\n".join(f"  - {o}" for o in objects)
    return f"""environment: {{name: empty, time: {{strategy: fixed_step}}}}
robots:
  - name: r
    type: fake_robot
    translate: {list(at)}
    rotate: {list(rotate)}
    components:
      - {camera}
objects:
{objs}
"""


def box(name, center, size=(0.5, 0.5, 0.5), props="Object: true", rotate=(0.0, 0.0, 0.0)) -> str:
    props = f", properties: {{{props}}}" if props else ""
    return f"{{name: {name}, type: box, translate: {list(center)}, rotate: {list(rotate)}, size: {list(size)}{props}}}"


def seen(sim, fqn: str = "r.sem") -> dict:
    return {o["name"]: o for o in sim.data(fqn)["visible_objects"]}


LAYOUT = [
    box("front", (3.0, 0.8, 1.0), props="Object: true, Label: FRONT, Description: a red box, Type: box",
        rotate=(0.0, 0.0, 0.5)),
    box("hidden", (6.0, -0.3, 1.0)),
    box("wall", (4.5, -0.3, 1.0), size=(0.2, 1.5, 2.0), props=""),  # not tagged: hides, is not reported
    box("aside", (0.0, 3.0, 1.0)),  # 90 degrees to the left
    box("behind", (-3.0, 0.0, 1.0)),
    box("untagged", (3.0, -0.8, 1.0), props="Label: plain"),
    box("far", (150.0, 0.0, 1.0), size=(1.0, 1.0, 1.0)),  # beyond cam_far (100 m)
]


def test_sees_the_object_in_front_not_the_hidden_one_nor_those_outside(tmp_path):
    with simulate(scene(LAYOUT), tmp_path) as sim:
        sim.step(3)
        objects = seen(sim)
        assert set(objects) == {"FRONT"}
        front = objects["FRONT"]
        assert front["description"] == "a red box" and front["type"] == "box"
        assert front["position"] == pytest.approx([3.0, 0.8, 1.0])
        # yaw 0.5 about z: quaternion (x, y, z, w) = (0, 0, sin 0.25, cos 0.25)
        assert [front["orientation"][k] for k in "xyzw"] == pytest.approx([0.0, 0.0, math.sin(0.25), math.cos(0.25)])
        assert list(front) == ["name", "description", "type", "position", "orientation"]
        # straight JSON of local_data on the socket stream, as MORSE
        message = json.loads(encode(sim.component("r.sem").serialize()))
        assert message["visible_objects"][0]["name"] == "FRONT"
        assert list(message) == ["timestamp", "visible_objects", "intrinsic_matrix"]


def test_noocclusion_reports_hidden_objects(tmp_path):
    camera = "{name: sem, type: semantic_camera, properties: {noocclusion: true}}"
    with simulate(scene(LAYOUT, camera), tmp_path) as sim:
        sim.step(3)
        objects = seen(sim)
        assert set(objects) == {"FRONT", "hidden"}
        assert objects["hidden"]["name"] == "hidden" and objects["hidden"]["type"] == ""


def test_bounding_box_meeting_the_frustum_is_enough(tmp_path):
    """A 1 m box centred at (3, 1.6): its centre is outside the view (1.6 / 3 > 0.457) but its near left
    corner (2.5, 1.1) is inside (1.1 / 2.5 = 0.44): seen. At (3, 2.5) it spans y 2.0..3.0, outside the
    view (at most 0.457 * 3.5 = 1.6 at its far face): not seen. Narrowing the view (cam_focal 60: 16 / 60 =
    0.267, at most 0.93 m at the far face) hides the first one too."""
    objects = [box("edge", (3.0, 1.6, 1.0), size=(1.0, 1.0, 1.0)), box("out", (3.0, -2.5, 1.0), size=(1.0, 1.0, 1.0))]
    with simulate(scene(objects), tmp_path) as sim:
        sim.step(3)
        assert set(seen(sim)) == {"edge"}
    narrow = "{name: sem, type: semantic_camera, properties: {cam_focal: 60.0}}"
    with simulate(scene(objects, narrow), tmp_path, name="narrow") as sim:
        sim.step(3)
        assert seen(sim) == {}


def test_near_and_far_clip(tmp_path):
    camera = "{name: sem, type: semantic_camera, properties: {cam_near: 2.5, cam_far: 4.0}}"
    objects = [box("close", (1.5, 0.5, 1.0)), box("mid", (3.0, 0.0, 1.0)), box("beyond", (5.0, 0.6, 1.0))]
    with simulate(scene(objects, camera), tmp_path) as sim:
        sim.step(3)
        assert set(seen(sim)) == {"mid"}


def test_relative_poses_are_in_the_camera_frame(tmp_path):
    """MORSE's camera frame: x right, y down, z forward. The robot turned 90 degrees left looks along world
    +y: an object at world (0.5, 3, 1.2) is 3 m ahead (z), 0.5 m to the right (x) and 0.2 m up (y = -0.2)
    in the camera frame; the camera frame's axes are world (1, 0, 0), (0, 0, -1), (0, 1, 0), so the
    object's world orientation (not turned) is their inverse there."""
    camera = "{name: sem, type: semantic_camera, properties: {relative: true}}"
    objects = [box("target", (0.5, 3.0, 1.2)), box("ahead_in_world", (3.0, 0.0, 1.0))]
    with simulate(scene(objects, camera, rotate=(0.0, 0.0, math.pi / 2)), tmp_path) as sim:
        sim.step(3)
        objects = seen(sim)
        assert set(objects) == {"target"}
        assert objects["target"]["position"] == pytest.approx([0.5, -0.2, 3.0], abs=1e-9)
        q = objects["target"]["orientation"]
        # rotation matrix rows (1, 0, 0), (0, 0, -1), (0, 1, 0): 90 degrees about x
        assert [q[k] for k in "xyzw"] == pytest.approx([math.sin(math.pi / 4), 0.0, 0.0, math.cos(math.pi / 4)])


def test_tag_selects_by_property_or_type(tmp_path):
    camera = "{name: sem, type: semantic_camera, properties: {tag: Bottle}}"
    objects = [box("typed", (3.0, 0.5, 1.0), props="Type: Bottle"),
               box("flagged", (3.0, -0.5, 1.0), props="Bottle: true"),
               box("other", (3.0, 0.0, 1.6), props="Object: true, Type: Glass")]
    with simulate(scene(objects, camera), tmp_path) as sim:
        sim.step(3)
        objects = seen(sim)
        assert set(objects) == {"typed", "flagged"}
        assert objects["typed"]["type"] == "Bottle" and objects["flagged"]["type"] == ""


def test_robots_are_tracked_and_the_own_robot_does_not_hide_anything(tmp_path):
    """A camera inside its own robot's chassis (an ATRV) still sees what is ahead; another tagged robot is
    reported like an object; the robot carrying the camera is not reported."""
    text = """environment: {name: empty, time: {strategy: fixed_step}}
robots:
  - name: r
    type: atrv
    components:
      - {name: sem, type: semantic_camera, translate: [0.0, 0.0, 0.1], properties: {tag: Robot_Tag}}
  - {name: other, type: atrv, translate: [4.0, 0.0, 0.0]}
"""
    with simulate(text, tmp_path) as sim:
        sim.step(3)
        objects = seen(sim)
        assert set(objects) == {"other"}
        assert objects["other"]["position"][0] == pytest.approx(4.0, abs=0.05)


def test_renders_nothing(tmp_path, monkeypatch):
    """No OpenGL needed: the semantic camera starts and works with a renderer that cannot be created."""
    def broken(*args, **kwargs):
        raise RuntimeError("no GL here")

    monkeypatch.setattr(mujoco, "Renderer", broken)
    with simulate(scene(LAYOUT), tmp_path) as sim:
        sim.step(3)
        assert set(seen(sim)) == {"FRONT"}
        assert sim.data("r.sem")["intrinsic_matrix"] == [[280.0, 0.0, 128.0], [0.0, 280.0, 128.0], [0.0, 0.0, 1.0]]


def test_sees_the_named_boxes_of_morses_boxes_environment(tmp_path):
    """MORSE's semantic_camera_testing: in `indoors-1/boxes` a camera at the origin turned 5/4 pi sees the
    box MORSE's .blend called BlueBox (game property Object = 'BlueBox'), turned pi from (-5, 0) RedBox;
    a scene object of the same name replaces the environment's."""
    text = """environment: {name: indoors-1/boxes, time: {strategy: fixed_step}}
robots:
  - name: r
    type: fake_robot
    translate: [0.0, 0.0, 0.86]
    rotate: [0.0, 0.0, 3.9269908169872414]
    components:
      - {name: sem, type: semantic_camera}
      - {name: tp, type: teleport}
"""
    with simulate(text, tmp_path) as sim:
        sim.step(2)
        objects = seen(sim)
        assert set(objects) == {"BlueBox"}
        assert objects["BlueBox"]["position"][:2] == pytest.approx([-3.5, -3.0], abs=1e-9)
        sim.command("r.tp", x=-5.0, y=0.0, z=0.86, roll=0.0, pitch=0.0, yaw=math.pi)
        sim.step(2)
        assert set(seen(sim)) == {"RedBox"}
    moved = text + "objects:\n  - {name: BlueBox, type: box, translate: [-3.5, 3.0, 0.5], properties: {Object: true}}\n"
    with simulate(moved, tmp_path) as sim:
        sim.step(2)
        assert seen(sim) == {}


def test_builder_script_tags_an_environment_object_and_reads_it_in_the_camera_frame(tmp_path):
    """A builder script reaches an object of the environment (indoors-1/boxes' RedBox) with
    bpymorse.get_object and gives it the Type a `tag` camera tracks: the camera then sees it, not the
    other boxes. `relative` poses are in MORSE's camera frame (x right, y down, z forward): RedBox
    (world -7.5, 0, 0.965, not turned) seen from a camera 0.3 m ahead of and 0.762 m above an ATRV at
    (-5, 0) facing -x (its origin rests 0.1 m above the floor: the camera at 0.862 m) is 2.2 m ahead and
    0.103 m up; its orientation there is the camera frame's inverse."""
    from morsec.app.project import build_scene
    from morsec.component.catalogue import load_catalogue
    from morsec.runtime.simulation import RunOptions, Simulation
    from morsec.testing import Harness

    script = tmp_path / "tagged.py"
    script.write_text("""from morse.builder import *
robot = ATRV()
robot.translate(x=-5.0)
robot.rotate(z=math.pi)
camera = SemanticCamera()
camera.properties(tag="Box", relative=True)
camera.translate(x=0.3, z=0.762)
robot.append(camera)
env = Environment('indoors-1/boxes')
bpymorse.properties(bpymorse.get_object('RedBox'), Type="Box")
""")
    build = build_scene(script, tmp_path / "build", load_catalogue())
    sim = Harness(Simulation(build, RunOptions(strategy="fixed_step", output_dir=tmp_path, service_port=0,
                                               port_base=0)))
    try:
        sim.run_for(0.3)
        objects = seen(sim, "robot.camera")
        assert set(objects) == {"RedBox"}  # BlueBox and GreenBox are tagged Object, not Box
        red = objects["RedBox"]
        assert red["type"] == "Box"
        assert red["position"] == pytest.approx([0.0, 0.862 - 0.965, 2.2], abs=0.005)
        assert [red["orientation"][k] for k in "xyzw"] == pytest.approx([0.5, 0.5, -0.5, 0.5], abs=1e-3)
    finally:
        sim.sim.close()
