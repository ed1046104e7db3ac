"""MORSE's props/objects props (BlackVideotape, WhiteVideotape, RollingChair): their own size, colour,
mass and origin, as a scene entry's defaults; MORSE's PassiveObject(file, name) in builder scripts, for a
catalogue prop or an object taken out of a catalogue environment, and its errors."""

from __future__ import annotations

import pytest

from morsec.app.process import record_call
from morsec.errors import SceneError
from morsec.testing import simulate


def test_props_have_their_own_size_mass_and_origin_on_the_floor(tmp_path):
    text = """
environment: {name: empty, time: {strategy: fixed_step, relative: true}}
objects:
  - {name: tape, type: BlackVideotape, translate: [1.0, 0.0, 0.0]}
  - {name: tape2, type: WhiteVideotape, translate: [1.0, 1.0, 0.0], properties: {Graspable: true}}
  - {name: big, type: BlackVideotape, translate: [1.0, -1.0, 0.0], size: [0.08, 0.24, 0.4], color: [1, 0, 0]}
  - {name: chair, type: RollingChair, translate: [0.0, 3.0, 0.01]}
"""
    with simulate(text, tmp_path) as h:
        model = h.sim.model
        objects = {o["name"]: o for o in h.sim.scene["objects"]}
        assert objects["tape"]["size"] == [0.04, 0.12, 0.2] and objects["tape"]["dynamic"] is True
        assert objects["tape"]["color"] == [0.0, 0.0, 0.0] and objects["tape2"]["color"] == [0.753, 0.753, 0.753]
        assert objects["tape2"]["properties"] == {"Graspable": True}
        assert objects["big"]["size"] == [0.08, 0.24, 0.4] and objects["big"]["color"] == [1, 0, 0]
        for name, mass in (("tape", 1.0), ("chair", 1.0)):
            body = h.sim.objects[[o.name for o in h.sim.objects].index(name)].body_id
            assert model.body_subtreemass[body] == pytest.approx(mass)
        h.run_for(1.0)
        # origins at the bottom: standing on the floor, their origin is at z = 0
        assert h.body_pose("tape")[0] == pytest.approx([1.0, 0.0, 0.0], abs=2e-3)
        assert h.body_pose("big")[0] == pytest.approx([1.0, -1.0, 0.0], abs=2e-3)
        assert h.body_pose("chair")[0] == pytest.approx([0.0, 3.0, 0.0], abs=2e-3)


def chair_and_tapes():
    from morsec.builder import ATRV, Environment, PassiveObject
    robot = ATRV()  # noqa: F841
    tape = PassiveObject("props/objects", "BlackVideotape")
    tape.translate(x=5, y=5)
    chair = PassiveObject(prefix="RollingChair")
    chair.translate(y=3, z=0.01)
    block = PassiveObject("environments/indoors-1/boxes", "GreenBox")
    block.translate(x=2, z=1)
    env = Environment("empty")  # noqa: F841


def test_passive_object_takes_a_catalogue_prop_or_an_environment_object():
    objects = {o["name"]: o for o in record_call(chair_and_tapes).data["objects"]}
    assert objects["tape"] == {"name": "tape", "type": "BlackVideotape", "translate": [5.0, 5.0, 0.0]}
    assert objects["chair"]["type"] == "RollingChair"
    # MORSE's GreenBox of boxes.blend, placed at the origin then moved (MORSE resets the pose)
    assert objects["block"] == {"name": "block", "type": "box", "size": [1.0, 1.0, 1.8],
                                "color": [0.0, 0.952, 0.019], "properties": {"Object": "GreenBox"},
                                "translate": [2.0, 0.0, 1.0]}


def unknown_box():
    from morsec.builder import PassiveObject
    PassiveObject("environments/indoors-1/boxes", "GreenBx")


def unknown_prop():
    from morsec.builder import PassiveObject
    PassiveObject("props/objects", "BlackVideotap")


def test_an_unknown_name_says_what_exists():
    with pytest.raises(SceneError, match="has no object 'GreenBx'; did you mean 'GreenBox'") as err:
        record_call(unknown_box)
    assert err.value.line == unknown_box.__code__.co_firstlineno + 2
    with pytest.raises(SceneError, match="no catalogue prop by that name; did you mean .*'BlackVideotape'"):
        record_call(unknown_prop)
