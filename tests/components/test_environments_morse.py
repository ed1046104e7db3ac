"""MORSE's environments rebuilt from what is known of them (components/environments/*/README.md): each one's
extent, its named objects with their game properties, a robot driving on its ground or terrain, the water of
the water scenes, and the names a MORSE builder script gives them."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from morsec.app.process import record_call
from morsec.component.catalogue import load_catalogue
from morsec.errors import SceneError
from morsec.frontends.load import load_scene
from morsec.kits import land1
from morsec.testing import simulate

# environment: (the ground's geom, its x and y extents as its README states them, where the README's robot stands)
WORLDS = {
    "indoors-1/indoor-1": ("env/ground", (-19.6, 19.6), (-15.0, 15.0), (0.0, 0.0)),
    "human_tut/tutorial_scene": ("env/ground", (-4.0, 4.0), (-6.0, 6.0), (0.0, -2.0)),
    "apartment": ("env/ground", (-10.9, 10.9), (-10.9, 10.9), (-1.0, -5.0)),
    "laas/grande_salle": ("env/ground", (-6.39, 11.31), (-10.99, 4.01), (6.0, -3.0)),
    "tum_kitchen/tum_kitchen": ("env/ground", (0.0, 8.21), (-3.04, 8.71), (1.5, 6.0)),
    "land-1/trees": ("env/ground", (-60.6, 60.7), (-74.6, 73.6), (0.0, 0.0)),
    "land-1/buildings_1": ("env/ground", (-60.6, 60.7), (-74.6, 73.6), (0.0, 0.0)),
    "land-1/buildings_2": ("env/ground", (-60.6, 60.7), (-74.6, 73.6), (0.0, -4.0)),
    "outdoors": ("env/ground", (-60.6, 60.7), (-74.6, 73.6), (-5.0, 0.0)),
    "water-1/water_scene": ("env/ground", (-60.6, 60.7), (-74.6, 73.6), (0.0, 0.0)),
}
# the highest point of the ground in the land-1 worlds (MORSE's heights)
HEIGHTS = {"land-1/trees": 2.83, "land-1/buildings_2": 2.83, "outdoors": 4.15, "land-1/buildings_1": 11.15,
           "water-1/water_scene": 11.15}


def _geom_box(model, data, name: str) -> tuple[np.ndarray, np.ndarray]:
    """The world-frame bounding box of a geom (a box's, a height field's)."""
    g = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, name)
    assert g >= 0, f"no geom {name}"
    if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_HFIELD:
        rx, ry, top, base = model.hfield_size[model.geom_dataid[g]]
        half, low = np.array([rx, ry]), np.array([-rx, -ry, -base])
        centre = data.geom_xpos[g]
        return centre + low, centre + np.array([*half, top])
    half = model.geom_size[g]
    return data.geom_xpos[g] - half, data.geom_xpos[g] + half


@pytest.mark.parametrize("world", sorted(WORLDS))
def test_a_robot_drives_on_the_ground_its_readme_promises(world, tmp_path):
    ground, xs, ys, (x, y) = WORLDS[world]
    text = f"""
environment: {{name: {world}, time: {{strategy: fixed_step, relative: true}}}}
robots:
  - name: robot
    type: atrv
    translate: [{x}, {y}, 0.0]
    components:
      - {{name: motion, type: motion_vw}}
"""
    with simulate(text, tmp_path) as h:
        lo, hi = _geom_box(h.sim.model, h.sim.data, ground)
        assert (lo[0], hi[0]) == pytest.approx(xs, abs=0.02) and (lo[1], hi[1]) == pytest.approx(ys, abs=0.02)
        bounds = load_catalogue().get("environments", world).bounds  # what the gallery frames: the ground, at least
        assert bounds is not None and bounds[0][0] <= xs[0] + 0.02 and bounds[1][0] >= xs[1] - 0.02
        assert bounds[0][1] <= ys[0] + 0.02 and bounds[1][1] >= ys[1] - 0.02
        if world in HEIGHTS:  # a terrain as high as MORSE's over the same extent, its valley at z = 0
            relief_lo, relief_hi = _geom_box(h.sim.model, h.sim.data, "env/ground_relief")
            assert relief_lo[:2] == pytest.approx(lo[:2], abs=1e-6) and relief_hi[:2] == pytest.approx(hi[:2], abs=1e-6)
            assert relief_hi[2] == pytest.approx(HEIGHTS[world] - 0.02, abs=0.01) and hi[2] == pytest.approx(0.0)
        h.run_for(0.5)
        start = h.body_pose("robot")[0]
        assert 0.0 < start[2] < 0.3  # standing on the ground at the origin's height, not in it nor falling
        h.command("robot.motion", v=1.0, w=0.0)
        h.run_for(2.0)
        end = h.body_pose("robot")[0]
        assert end[0] - start[0] == pytest.approx(2.0, abs=0.3)  # drove 2 m along x: nothing in the way
        assert abs(end[2] - start[2]) < 0.3  # still on the ground


def test_indoor_1_has_morses_tagged_objects_that_a_semantic_camera_reports(tmp_path):
    # MORSE's first tutorial: a robot at the origin turned towards the RedBox, 2.2 m away, sees it
    text = """
environment: {name: indoors-1/indoor-1, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: atrv
    rotate: [0.0, 0.0, 2.29]
    components:
      - {name: camera, type: semantic_camera, translate: [0.3, 0.0, 0.9]}
"""
    with simulate(text, tmp_path) as h:
        objects = {o.name: o for o in h.sim.objects}
        assert {name: objects[name].properties for name in ("RedBox", "GreenBox", "PinkBox", "YellowBox", "Bottle1")} == {
            "RedBox": {"Object": True}, "GreenBox": {"Object": True}, "PinkBox": {"Object": True, "Graspable": True},
            "YellowBox": {"Object": "Box"}, "Bottle1": {"Object": True, "Graspable": True}}
        model = h.sim.model
        for name, mass in (("RedBox", 5.0), ("GreenBox", 4.0), ("PinkBox", 3.0), ("YellowBox", 5.0), ("Bottle1", 1.0)):
            assert model.body_subtreemass[objects[name].body_id] == pytest.approx(mass)
        h.run_for(1.0)
        # the boxes on desks rest on them (they are dynamic): the pink one on Desk_3.002, 0.96 m high
        assert h.body_pose("PinkBox")[0][2] == pytest.approx(0.96 + 0.25, abs=0.02)
        assert h.body_pose("YellowBox")[0][2] == pytest.approx(1.35 + 0.42, abs=0.02)
        seen = {o["name"]: o for o in h.data("robot.camera")["visible_objects"]}
        assert "RedBox" in seen
        assert seen["RedBox"]["position"] == pytest.approx([-1.47, 1.69, 0.5], abs=0.05)
        assert "GreenBox" not in seen  # 12 m away, out of the camera's field


def test_the_human_tutorials_cup_and_labelled_doors(tmp_path):
    # the robot in the doorway looking west at the table: the semantic camera reports the cup by its Label
    text = """
environment: {name: human_tut/tutorial_scene, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: atrv
    translate: [0.5, 2.1, 0.0]
    rotate: [0.0, 0.0, 3.1416]
    components:
      - {name: camera, type: semantic_camera, translate: [0.3, 0.0, 0.9]}
"""
    with simulate(text, tmp_path) as h:
        objects = {o.name: o.properties for o in h.sim.objects}
        assert objects["CubeSelect"] == {"Object": True, "Description": "Cup", "Label": "Cup", "Type": "",
                                         "Graspable": True}
        assert objects["Drawers_Drawer_002"] == {"Drawer": "Drawers_Drawer.002", "Open": False,
                                                 "Description": "Drawer", "Label": "Drawer"}
        assert objects["Shelf_UpperDoor_L"]["Label"] == "Shelf Door"
        assert len([n for n in objects if n.startswith(("Drawers_", "Shelf_"))]) == 12
        h.run_for(1.0)
        assert h.body_pose("CubeSelect")[0] == pytest.approx([-3.225, 2.125, 0.9 + 0.085], abs=0.02)  # on the table
        seen = [o["name"] for o in h.data("robot.camera")["visible_objects"]]
        assert seen == ["Cup"]


def test_the_tutorial_rooms_doorway_opens_on_the_trail(tmp_path):
    text = """
environment: {name: human_tut/tutorial_scene, time: {strategy: fixed_step, relative: true}}
robots:
  - {name: robot, type: atrv, translate: [2.0, 0.0, 0.0], components: [{name: motion, type: motion_vw}]}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(0.5)
        h.command("robot.motion", v=1.0, w=0.0)
        h.run_for(6.0)
        x, y, z = h.body_pose("robot")[0]
        assert x > 7.0 and abs(y) < 0.3 and z > 0.0  # out through the doorway and along the trail


def test_the_kitchens_chair_and_fridge_carry_morses_properties(tmp_path):
    text = """
environment: {name: tum_kitchen/tum_kitchen, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: atrv
    translate: [5.6, -1.9, 0.0]
    rotate: [0.0, 0.0, 3.1416]
    components:
      - {name: camera, type: semantic_camera, translate: [0.3, 0.0, 0.9]}
"""
    with simulate(text, tmp_path) as h:
        objects = {o.name: o.properties for o in h.sim.objects}
        assert objects["Chair1"] == {"Object": "chair", "Description": "chair", "Graspable": True}
        assert objects["v1_node10_visual"] == {"Door": "right", "Open": False, "Description": "Fridge"}
        assert {objects[n]["Drawer"] for n in ("v1_node81_visual", "v1_node90_visual")} == {"Drawer", "Drawer2"}
        h.run_for(0.5)
        assert [o["name"] for o in h.data("robot.camera")["visible_objects"]] == ["Chair1"]


def test_the_water_scene_has_water_over_its_valley(tmp_path):
    text = """
environment: {name: water-1/water_scene, time: {strategy: fixed_step, relative: true}}
robots:
  - {name: sub, type: submarine, translate: [0.0, -5.0, 2.0]}
  - {name: rover, type: atrv, translate: [0.0, 30.0, 11.3]}
"""
    with simulate(text, tmp_path) as h:
        model = h.sim.model
        water = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "env/water")
        assert h.sim.data.geom_xpos[water][2] == pytest.approx(4.2)
        assert model.geom_size[water][:2] == pytest.approx([63.0, 63.0])
        assert model.geom_contype[water] == 0 and model.geom_conaffinity[water] == 0  # nothing collides with it
        assert model.mat_rgba[model.geom_matid[water]][3] == pytest.approx(0.5)  # half transparent
        h.run_for(1.0)
        assert h.body_pose("sub")[0] == pytest.approx([0.0, -5.0, 2.0], abs=0.01)  # under water, where it was put
        assert h.body_pose("rover")[0][2] > 10.5  # on the plateau, an island above the water


def test_the_grande_salles_rolling_chairs_are_morses_prop(tmp_path):
    text = "environment: {name: laas/grande_salle, time: {strategy: fixed_step, relative: true}}\n"
    with simulate(text, tmp_path) as h:
        chairs = [o for o in h.sim.scene["objects"] if o["name"].startswith("Rolling_Chair")]
        assert len(chairs) == 12 and {c["type"] for c in chairs} == {"RollingChair"}
        h.run_for(1.0)
        # where MORSE's stand, its seat under a desk (a top on legs), untouched by it
        assert h.body_pose("Rolling_Chair_007")[0] == pytest.approx([5.66, -6.63, 0.0], abs=0.01)


@pytest.mark.parametrize(("name", "world"), [
    ("indoors-1/indoor-1", "indoors-1/indoor-1"),
    ("indoors-1/indoor-1.blend", "indoors-1/indoor-1"),
    ("indoor-1", "indoors-1/indoor-1"),
    ("tum_kitchen.blend", "tum_kitchen/tum_kitchen"),
    ("environments/laas/grande_salle", "laas/grande_salle"),
    ("/usr/share/morse/data/environments/water-1/water_scene.blend", "water-1/water_scene"),
    ("outdoors", "outdoors"),
])
def test_a_builder_script_names_them_as_morse_did(name, world):
    def scene():
        from morsec.builder import ATRV, Environment
        robot = ATRV()  # noqa: F841
        env = Environment(name)  # noqa: F841
    assert record_call(scene).data["environment"]["name"] == world


@pytest.mark.parametrize("name", ["indoors-1/indoor-2", "indoor-2.blend"])
def test_an_unknown_environment_is_an_error_with_did_you_mean(name, tmp_path):
    script = tmp_path / "scene.py"
    script.write_text(f"from morse.builder import *\nrobot = ATRV()\nenv = Environment({name!r})\n")
    with pytest.raises(SceneError, match=r"unknown environment '.*indoor-2'.*did you mean.*'indoors-1/indoor-1'") as err:
        load_scene(script)
    assert err.value.line == 3


def test_a_terrains_heights_are_where_its_function_puts_them(tmp_path):
    # a ray down onto the land-1 ground meets it at the height morsec.kits.land1 gives there
    with simulate("environment: {name: land-1/trees}\n", tmp_path) as h:
        model, data = h.sim.model, h.sim.data
        geom = np.zeros(1, np.int32)
        for x, y in ((0.0, 0.0), (25.0, 20.0), (-56.0, -42.0), (35.0, -30.0), (-40.0, 60.0), (0.0, 12.0)):
            drop = mujoco.mj_ray(model, data, np.array([x, y, 50.0]), np.array([0.0, 0.0, -1.0]), None, 1, -1, geom)
            hit = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, geom[0])
            expected = 2.83 * land1.height(x, y)
            assert hit == ("env/ground_relief" if expected > 0.02 else "env/ground")
            assert 50.0 - drop == pytest.approx(max(expected - 0.02, 0.0), abs=0.05)
