"""MORSE's middlewares that morsec refuses (YARP, MOOS, pocolibs, HLA): a builder script or a YAML scene that
names one stops at that line with one line saying why and what to use instead, as docs/coming-from-morse.md
lists them."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from morsec.errors import SceneError
from morsec.frontends.load import load_scene
from morsec.middleware.refused import DOCS, REFUSED, refusal

ROOT = Path(__file__).resolve().parent.parent
MORSEC = Path(sys.executable).with_name("morsec")
CALLS = {  # a MORSE builder call naming a middleware -> where the scene records it
    "pose.add_stream('{mw}')": "robots[0].components[0].streams[0]",
    "pose.add_service('{mw}')": "robots[0].components[0].services[0]",
    "robot.add_default_interface('{mw}')": "robots[0].default_interface",
}


def script(tmp_path: Path, call: str) -> Path:
    path = tmp_path / "mysim.py"
    path.write_text("from morse.builder import *\nrobot = ATRV()\npose = Pose()\nrobot.append(pose)\n"
                    f"{call}\nenv = Environment('empty')\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("middleware", sorted(REFUSED))
@pytest.mark.parametrize("call", sorted(CALLS))
def test_a_builder_call_naming_a_refused_middleware_gets_its_one_line(middleware, call, tmp_path):
    path = script(tmp_path, call.format(mw=middleware))
    with pytest.raises(SceneError) as caught:
        load_scene(path)
    message = str(caught.value)
    assert message == f"{path}:5:1: {CALLS[call]}: {refusal(middleware)}"
    assert "\n" not in message
    refused = REFUSED[middleware]
    assert refused.reason in message and refused.instead in message and DOCS in message


def test_morsec_build_refuses_add_stream_yarp_in_one_line(tmp_path):
    path = script(tmp_path, "pose.add_stream('yarp')")
    result = subprocess.run([str(MORSEC), "build", str(path), "-o", str(tmp_path / "build")], capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 2
    assert result.stderr.splitlines() == [f"error: {path}:5:1: robots[0].components[0].streams[0]: "
                                          f"{refusal('yarp')}"]


def test_a_yaml_scene_naming_a_refused_middleware_gets_its_one_line(tmp_path):
    path = tmp_path / "scene.yaml"
    path.write_text("environment: {name: empty}\nrobots:\n  - name: robot\n    type: atrv\n    components:\n"
                    "      - {name: pose, type: pose, streams: [{middleware: MOOS}]}\n", encoding="utf-8")
    with pytest.raises(SceneError) as caught:
        load_scene(path)
    assert str(caught.value) == f"{path}:6:57: robots[0].components[0].streams[0].middleware: {refusal('moos')}"


def test_a_binding_to_morses_yarp_datastream_gets_the_refusal(tmp_path):
    path = script(tmp_path, "pose.configure_mw(['morse.middleware.yarp_datastream.YarpDatastreamManager', 'post', 'x'])")
    with pytest.raises(SceneError) as caught:
        load_scene(path)
    assert str(caught.value) == (f"{path}:5:1: configure_mw(['morse.middleware.yarp_datastream.YarpDatastreamManager', "
                                 f"'post', 'x']): {refusal('yarp')}")


def test_an_unknown_middleware_still_lists_those_morsec_has(tmp_path):
    with pytest.raises(SceneError) as caught:
        load_scene(script(tmp_path, "pose.add_stream('mavros')"))
    assert "'mavros' is not one of" in str(caught.value) and "'socket'" in str(caught.value)


def test_coming_from_morse_lists_each_refusal_with_its_reason_and_alternative():
    page = (ROOT / "docs" / "coming-from-morse.md").read_text(encoding="utf-8")
    anchor = DOCS.split("#", 1)[1]
    assert re.search(rf"^### {anchor.replace('-', ' ').capitalize()}$", page, re.M), f"no section #{anchor}"
    for refused in REFUSED.values():
        assert f"| `{refused.name}` | {refused.reason} | {refused.instead} |" in page, refused.name
