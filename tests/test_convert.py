"""`morsec convert`: any scene form into another; building the result gives the same build."""

from __future__ import annotations

import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import pytest
import yaml

from morsec.app.convert import convert_scene, to_toml, to_yaml
from morsec.compiler.build import compile_scene
from morsec.component.catalogue import load_catalogue
from morsec.errors import SceneError
from morsec.frontends import load_scene

ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "scenes"
SCRIPTS = Path(__file__).resolve().parent / "builder_scripts"
MORSEC = Path(sys.executable).parent / "morsec"


def build_files(path: Path) -> dict[str, str]:
    cat = load_catalogue(path.parent)
    return compile_scene(load_scene(path, cat), cat)


def sources() -> list[Path]:
    return sorted([*SCENES.glob("*.py"), *SCENES.glob("*.yaml"), *SCENES.glob("*.toml"), *SCRIPTS.glob("*.py")])


@pytest.mark.parametrize("source,suffix", [(s, x) for s in sources() for x in (".yaml", ".toml") if s.suffix != x],
                         ids=lambda v: f"{v.parent.name}/{v.name}" if isinstance(v, Path) else v)
def test_converted_scene_builds_the_same(source, suffix, tmp_path, capsys):
    target = convert_scene(source, tmp_path / f"converted{suffix}")
    assert build_files(target) == build_files(source)


@pytest.mark.parametrize("source", sorted(SCENES.glob("*.yaml")), ids=lambda p: p.name)
def test_yaml_toml_yaml_round_trip(source, tmp_path):
    toml_file = convert_scene(source, tmp_path / "a.toml")
    yaml_file = convert_scene(toml_file, tmp_path / "b.yml")
    assert yaml.safe_load(yaml_file.read_text()) == yaml.safe_load(source.read_text())
    assert build_files(yaml_file) == build_files(source)


def test_converted_builder_script_reads_like_a_scene(tmp_path):
    target = convert_scene(SCENES / "tutorial.py", tmp_path / "tutorial.yaml")
    text = target.read_text()
    assert text.startswith("# converted from tutorial.py by `morsec convert`\n")
    data = yaml.safe_load(text)
    robot = data["robots"][0]
    assert (robot["name"], robot["type"], robot["default_interface"]) == ("robot", "atrv", "socket")
    assert "translate" not in robot  # only what the script says: no defaults written out
    assert [c["name"] for c in robot["components"]] == ["pose", "motion", "odo"]
    assert robot["components"][0]["translate"] == [0.0, 0.0, -0.1]
    assert data["objects"][0]["size"] == [0.5, 0.5, 0.5]
    assert data["zones"][0]["size"] == [5.0, 5.0, 5.0]
    assert "translate: [0.0, 0.0, -0.1]" in text  # vectors in flow style


def test_morse_only_settings_survive_conversion(tmp_path, capsys):
    script = tmp_path / "sim.py"
    script.write_text(textwrap.dedent("""
        from morse.builder import *
        robot = ATRV()
        robot.make_external()
        env = Environment('empty')
        env.set_horizon_color(color=(0.1, 0.2, 0.3))
    """))
    target = convert_scene(script, tmp_path / "sim.toml")
    data = tomllib.loads(target.read_text())
    assert data["environment"]["morse_only"] == {"robot.make_external": {}, "set_horizon_color": {"color": [0.1, 0.2, 0.3]}}
    assert build_files(target) == build_files(script)


def test_toml_writer_round_trips_awkward_data():
    data = {
        "environment": {"name": "empty", "properties": {"a key": 'quote " and \\ backslash', "new\nline": "x\ty",
                                                          "unicode": "é ✓", "big": 12345678901, "tiny": 1e-09,
                                                          "neg": -0.0, "flag": False},
                        "time": {"strategy": "fixed_step"}, "multinode": None,
                        "camera": {"location": [1, 2.5, -3.0], "rotation": [0.1, 0.2, 0.3], "clip": [0.1, 100.0]}},
        "robots": [
            {"name": "r", "type": "atrv", "properties": {},
             "components": [
                 {"name": "p", "type": "pose", "streams": ["socket", {"middleware": "socket", "port": 60100}],
                  "modifiers": [{"name": "noise", "pos_std": {"x": 0.1, "y": 0.2}}],
                  "components": [{"name": "q", "type": "pose"}]},
                 {"name": "m", "type": "motion_vw"}]},
            {"name": "s", "type": "atrv"},
        ],
        "objects": [],
    }
    text = to_toml(data, "header")
    back = tomllib.loads(text)
    expected = dict(data)
    expected["environment"] = {k: v for k, v in data["environment"].items() if v is not None}
    assert back == expected


def test_toml_cannot_hold_null_in_a_list():
    with pytest.raises(SceneError, match="null inside a list"):
        to_toml({"environment": {"properties": {"x": [1, None]}}})


def test_yaml_writer_round_trips_strings_that_look_like_other_types():
    data = {"environment": {"properties": {"a": "yes", "b": "1.0", "c": "null", "d": "~", "e": "on", "f": True}}}
    assert yaml.safe_load(to_yaml(data)) == data


def test_convert_refuses_unknown_forms_and_overwriting_the_source(tmp_path):
    with pytest.raises(SceneError, match="convert writes .yaml, .yml or .toml"):
        convert_scene(SCENES / "tutorial.yaml", tmp_path / "x.json")
    with pytest.raises(SceneError, match="the source must be .py, .yaml, .yml or .toml"):
        convert_scene(tmp_path / "x.json", tmp_path / "x.yaml")
    copy = tmp_path / "t.yaml"
    copy.write_text((SCENES / "tutorial.yaml").read_text())
    with pytest.raises(SceneError, match="is the source itself"):
        convert_scene(copy, tmp_path / "." / "t.yaml")


def test_invalid_source_is_reported_and_nothing_is_written(tmp_path):
    source = tmp_path / "bad.yaml"
    source.write_text("robots:\n  - type: atrv\n    translte: [0, 0, 0]\n")
    target = tmp_path / "bad.toml"
    with pytest.raises(SceneError) as info:
        convert_scene(source, target)
    assert str(info.value).startswith(f"{source}:3:5: robots[0].translte")
    assert not target.exists()


def test_cli_convert(tmp_path):
    target = tmp_path / "tutorial.toml"
    result = subprocess.run([str(MORSEC), "convert", str(SCENES / "tutorial.py"), "-o", str(target)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == f"converted {SCENES / 'tutorial.py'} -> {target}"
    assert build_files(target) == build_files(SCENES / "tutorial.yaml")
    result = subprocess.run([str(MORSEC), "convert", str(SCENES / "tutorial.py"), "-o", str(tmp_path / "x.xml")],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    assert result.stderr.strip() == f"error: {tmp_path / 'x.xml'}: cannot write '.xml'; convert writes .yaml, .yml or .toml"
