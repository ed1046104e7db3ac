"""The objects of MORSE's props files (components/props/{objects,misc_objects,crates,computer_parts}): MORSE's
names, sizes and masses, resting on the ground where they are put, seen by a semantic camera by the Label a
script gives them, named by builder scripts as MORSE's PassiveObject names them."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from morsec.app.process import record_call
from morsec.component.catalogue import load_catalogue
from morsec.errors import SceneError
from morsec.testing import simulate

CAT = load_catalogue()
FILES = ("objects", "misc_objects", "crates", "computer_parts")
OBJECTS = [(f, name) for f in FILES for name in CAT.get("props", f).variants]
# MORSE's sizes (x, y, z, m) and masses (kg) of some of them, read from its .blend files
MORSE = {"BlackVideotape": ((0.04, 0.12, 0.2), 1.0), "BlueToyTrashbin": ((0.37, 0.37, 0.277), 1.0),
         "Desk": ((1.648, 0.792, 0.728), 1.0), "Book_Wine_thin": ((0.02, 0.095, 0.151), 1.0),
         "Bottle": ((0.2, 0.2, 0.466), 1.12), "large_crate": ((4.02, 2.02, 2.0), 80.0),
         "small_crate": ((1.0, 1.0, 1.0), 20.0), "transport_box": ((2.096, 1.298, 0.878), 20.0),
         "cpu": ((0.462, 0.212, 0.482), 1.0), "monitor": ((0.268, 0.512, 0.447), 1.0)}


def test_every_object_of_morses_props_files_is_a_type():
    assert sorted(name for _, name in OBJECTS) == sorted([
        "BlackVideotape", "WhiteVideotape", "GreyVideotape", "BlueToyTrashbin", "PinkToyTrashbin", "BoxStand",
        "Desk", "IKEAShelf", "RollingChair", "SmallTable",
        *(f"Book_{c}_{w}" for c in ("Blue", "Brown", "Wine") for w in ("fat", "medium", "thin")), "Bottle",
        "large_crate", "cap_large_crate", "small_crate", "transport_box", "cpu", "keyboard", "laptop", "monitor"])
    for file, name in OBJECTS:
        assert CAT.resolve("props", name) == file
    for name, (size, mass) in MORSE.items():
        spec = CAT.variant(name)
        assert spec["size"] == pytest.approx(size, abs=0.005) and spec["mass"] == mass


def _bottom(model, data, body: int) -> float:
    """The lowest point of a body's geoms (boxes and upright cylinders), world frame."""
    low = np.inf
    for g in range(model.ngeom):
        if model.geom_bodyid[g] != body:
            continue
        half = model.geom_size[g] if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_BOX else \
            np.array([model.geom_size[g][0], model.geom_size[g][0], model.geom_size[g][1]])
        corners = np.abs(data.geom_xmat[g].reshape(3, 3)) @ half
        low = min(low, data.geom_xpos[g][2] - corners[2])
    return float(low)


@pytest.mark.parametrize("file", FILES)
def test_they_rest_on_the_ground_where_they_are_put(file, tmp_path):
    # each object put 2 cm above the floor (its origin lifted by how far its lowest part is under it), apart
    names = list(CAT.get("props", file).variants)
    entries = []
    for i, name in enumerate(names):
        spec = CAT.variant(name)
        lift = -min(p.centre[2] - p.size[2] / 2 for p in spec["parts"]) + 0.02
        entries.append(f"  - {{name: o{i}, type: {name}, translate: [{5.0 * i}, 0.0, {lift:.4f}]}}\n")
    text = "environment: {name: empty, time: {strategy: fixed_step, relative: true}}\nobjects:\n" + "".join(entries)
    with simulate(text, tmp_path) as h:
        h.run_for(1.0)
        model, data = h.sim.model, h.sim.data
        for i, name in enumerate(names):
            spec = CAT.variant(name)
            body = model.body(f"o{i}").id
            bottom = _bottom(model, data, body)
            if spec["dynamic"]:  # fell the 2 cm and lies on the floor, upright
                assert bottom == pytest.approx(0.0, abs=0.004), name
                assert model.body_subtreemass[body] == pytest.approx(spec["mass"]), name
                assert abs(data.xmat[body][8]) > 0.99, name
            else:  # static, as MORSE's: it stays where it was put
                assert bottom == pytest.approx(0.02, abs=1e-6), name


def test_a_semantic_camera_sees_them_by_the_label_a_script_gives(tmp_path):
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
robots:
  - name: robot
    type: atrv
    components:
      - {name: camera, type: semantic_camera, translate: [0.3, 0.0, 0.9]}
objects:
  - {name: bottle, type: Bottle, translate: [4.0, -0.5, 0.233], properties: {Object: true, Label: Bottle}}
  - {name: crate, type: small_crate, translate: [6.0, 1.0, 0.0], properties: {Object: true, Type: Crate}}
  - {name: tape, type: WhiteVideotape, translate: [4.0, 0.5, 0.0]}
"""
    with simulate(text, tmp_path) as h:
        h.run_for(0.5)
        seen = {o["name"]: o for o in h.data("robot.camera")["visible_objects"]}
        assert set(seen) == {"Bottle", "crate"}  # the untagged tape is not reported, as in MORSE
        assert seen["crate"]["type"] == "Crate"
        assert seen["Bottle"]["position"] == pytest.approx([4.0, -0.5, 0.233], abs=0.01)


def graspable_book():
    from morsec.builder import ATRV, Environment, PassiveObject
    robot = ATRV()  # noqa: F841
    book = PassiveObject("props/misc_objects.blend", "Book_Brown_fat")
    book.setgraspable()
    book.translate(x=2.0, z=0.1)
    big = PassiveObject("props/crates", "small_crate")
    big.scale = (2.0, 2.0, 2.0)
    env = Environment("empty")  # noqa: F841


def test_passive_object_names_the_file_and_the_object():
    objects = {o["name"]: o for o in record_call(graspable_book).data["objects"]}
    assert objects["book"]["type"] == "Book_Brown_fat"
    assert objects["book"]["translate"] == [2.0, 0.0, 0.1]
    assert objects["book"]["properties"] == {"Object": True, "Graspable": True, "Label": "book"}
    assert objects["big"]["size"] == [2.0, 2.0, 2.0]  # MORSE's scale of the 1 m crate


def whole_file():
    from morsec.builder import PassiveObject
    PassiveObject("props/crates")


def hud():
    from morsec.builder import PassiveObject
    PassiveObject("props/basics", "CameraFP")


def test_a_file_without_an_object_or_props_basics_is_a_one_line_error():
    with pytest.raises(SceneError, match=r"'crates' holds several objects: name one \(large_crate, cap_large_crate"):
        record_call(whole_file)
    with pytest.raises(SceneError, match="props/basics holds its viewer's camera and head-up display"):
        record_call(hud)
