"""Every mistake a user can make in a scene: exit code 2, one line `file:line:col: <yaml path>: <message>`,
a suggestion where one exists, no traceback, and nothing half-written.

The bad scenes live in tests/fixtures/errors/*.scene.yaml|toml (each says what is wrong in a comment);
here is where each error is reported and what it says, matched whole.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import textwrap
import xml.etree.ElementTree as ET
from pathlib import Path

import mujoco
import pytest

from morsec.app.project import build_scene
from morsec.compiler.build import compile_scene
from morsec.component.catalogue import load_catalogue
from morsec.errors import SceneError
from morsec.frontends import load_scene

ROOT = Path(__file__).resolve().parent.parent
FIXTURES = Path(__file__).resolve().parent / "fixtures" / "errors"
TUTORIAL = ROOT / "scenes" / "tutorial.yaml"
NAMES = r"(?:'[^']*'(?:, )?)+"  # a list of quoted catalogue names, which grows with the catalogue


@pytest.fixture(autouse=True)
def _builtin_catalogue(monkeypatch):
    """Only the built-in components, whatever the caller's environment says."""
    monkeypatch.delenv("MORSEC_COMPONENTS", raising=False)


def morsec(*args: str, cwd: Path | None = None, env: dict | None = None) -> subprocess.CompletedProcess:
    """The real command line, in a child process."""
    full_env = {k: v for k, v in os.environ.items() if k != "MORSEC_COMPONENTS"}
    full_env.update(env or {})
    return subprocess.run([sys.executable, "-c", "from morsec.cli import main; main()", *args],
                          capture_output=True, text=True, cwd=cwd or ROOT, env=full_env, timeout=120)


def scene_error(path: Path, *, compile: bool = False) -> SceneError:
    """The SceneError that loading (and, with compile, compiling) `path` raises."""
    with pytest.raises(SceneError) as info:
        cat = load_catalogue(path.parent)
        scene = load_scene(path, cat)
        if compile:
            compile_scene(scene, cat)
    return info.value


def assert_error(err: SceneError, file: Path, line: int, column: int, message: str) -> None:
    assert (err.file, err.line, err.column) == (str(file), line, column), str(err)
    assert re.fullmatch(message, err.message), f"{err.message!r} does not match {message!r}"


# ---------------------------------------------------------------- the fixtures, each at its position

CASES = [
    # syntax
    ("yaml_syntax.scene.yaml", 6, 1,
     r"YAML syntax error: expected ',' or '\]', but got '<stream end>' \(a flow sequence started at line 5, column 16\)"),
    ("toml_syntax.scene.toml", 4, 8,
     r"TOML syntax error: Invalid value \(strings need quotes; numbers, true, false, inf and nan do not\)"),
    # unknown keys at several depths, in YAML and TOML
    ("unknown_key_top.scene.yaml", 2, 1, r"robot: unknown key 'robot'; did you mean 'robots'\?"),
    ("unknown_key_robot.scene.yaml", 5, 5, r"robots\[0\]\.translat: unknown key 'translat'; did you mean 'translate'\?"),
    ("unknown_key_component.scene.yaml", 8, 9,
     r"robots\[0\]\.components\[0\]\.translte: unknown key 'translte'; did you mean 'translate'\?"),
    ("unknown_key_time.scene.yaml", 6, 5,
     r"environment\.time\.frequncy: unknown key 'frequncy'; did you mean 'frequency'\?"),
    ("unknown_key_stream.scene.toml", 15, 37,
     r"robots\[1\]\.components\[1\]\.streams\[0\]\.prot: unknown key 'prot'; did you mean 'port'\?"),
    # types and shapes
    ("wrong_type.scene.yaml", 4, 22, r"robots\[0\]\.translate\[1\]: must be a number, got the string 'one'"),
    ("translate_length.scene.yaml", 4, 16,
     r"robots\[0\]\.translate: must be a list of 3 numbers \[x, y, z\], got 2: \[1\.0, 2\.0\]"),
    ("translate_length.scene.toml", 4, 13,
     r"robots\[0\]\.translate: must be a list of 3 numbers \[x, y, z\], got 2: \[1\.0, 2\.0\]"),
    # unknown names, with close matches
    ("unknown_robot_type.scene.yaml", 4, 11, r"robots\[0\]\.type: unknown robot type 'atrvv'; did you mean 'atrv'\?"),
    ("unknown_component_type.scene.yaml", 5, 15,
     r"robots\[0\]\.components\[0\]\.type: unknown component type 'poze'; did you mean 'pose'\?"),
    ("unknown_environment.scene.yaml", 3, 9,
     rf"environment\.name: unknown environment 'sandbx' \(known: {NAMES}\); did you mean 'sandbox'\?"),
    ("unknown_level.scene.yaml", 6, 16,
     r"robots\[0\]\.components\[0\]\.level: unknown level 'diferential' of component type 'odometry' "
     r"\(levels: 'raw', 'differential', 'integrated'\); did you mean 'differential'\?"),
    ("unknown_property.scene.yaml", 4, 18,
     rf"robots\[0\]\.properties\.NoGravty: unknown property 'NoGravty' of robot type 'atrv' \(properties: {NAMES}\); "
     r"did you mean 'NoGravity'\?"),
    ("unknown_component_property.scene.yaml", 7, 11,
     rf"robots\[0\]\.components\[0\]\.properties\.ControlTyp: unknown property 'ControlTyp' of actuator type "
     rf"'motion_vw' \(properties: {NAMES}\); did you mean 'ControlType'\?"),
    ("unknown_without.scene.yaml", 4, 15,
     r"robots\[0\]\.without\[0\]: robot type 'nav_pr2' carries no component 'keybord' to leave out; "
     r"did you mean 'keyboard'\?"),
    # names
    ("duplicate_robot_names.scene.yaml", 5, 11,
     r"robots\[1\]\.name: duplicate name 'robot': robots and objects share one namespace; rename one of them"),
    ("duplicate_component_names.scene.yaml", 7, 16,
     r"robots\[0\]\.components\[1\]\.name: duplicate component name 'pose' under the same parent"),
    ("dotted_name.scene.yaml", 3, 11,
     r"robots\[0\]\.name: name 'my\.robot' contains '\.': names are joined with '\.' into fully-qualified names "
     r"\(robot\.child\) and sent over line-based protocols; try 'my_robot'"),
    ("name_with_space.scene.yaml", 5, 15,
     r"robots\[0\]\.components\[0\]\.name: name 'front pose' contains ' ': .*; try 'front_pose'"),
    # numbers
    ("zero_frequency.scene.yaml", 6, 20,
     r"robots\[0\]\.components\[0\]\.frequency: must be greater than 0, got 0"),
    ("negative_frequency.scene.yaml", 4, 16, r"environment\.time\.frequency: must be greater than 0, got -60"),
    ("nan.scene.yaml", 4, 22,
     r"robots\[0\]\.translate\[1\]: must be a finite number \(NaN and infinities are not allowed\), got nan"),
    ("inf.scene.yaml", 5, 17,
     r"objects\[0\]\.size\[1\]: must be a finite number \(NaN and infinities are not allowed\), got -inf"),
    ("nan.scene.toml", 7, 13,
     r"robots\[0\]\.components\[0\]\.frequency: must be a finite number \(NaN and infinities are not allowed\), got nan"),
    ("inf.scene.toml", 3, 11,
     r"environment\.gravity: must be a finite number \(NaN and infinities are not allowed\), got inf"),
]


@pytest.mark.parametrize("name, line, column, message", CASES, ids=[c[0] for c in CASES])
def test_fixture_error(name, line, column, message):
    path = FIXTURES / name
    assert_error(scene_error(path), path, line, column, message)


def test_every_fixture_is_tested():
    assert sorted(p.name for p in FIXTURES.glob("*.scene.*")) == sorted(c[0] for c in CASES)


@pytest.mark.parametrize("name", ["yaml_syntax.scene.yaml", "toml_syntax.scene.toml",
                                  "unknown_key_component.scene.yaml", "unknown_key_stream.scene.toml",
                                  "nan.scene.toml", "duplicate_component_names.scene.yaml"])
def test_cli_check_prints_one_line_and_exits_2(name):
    expected = next(c for c in CASES if c[0] == name)
    result = morsec("check", str(FIXTURES / name))
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    where = re.escape(f"error: {FIXTURES / name}:{expected[1]}:{expected[2]}: ")
    assert re.fullmatch(where + expected[3], lines[0]), lines[0]


def test_cli_build_of_a_bad_scene_writes_nothing(tmp_path):
    out = tmp_path / "out"
    result = morsec("build", str(FIXTURES / "unknown_key_robot.scene.yaml"), "-o", str(out))
    assert result.returncode == 2
    assert re.fullmatch(r"error: .*unknown_key_robot\.scene\.yaml:5:5: robots\[0\]\.translat: unknown key "
                        r"'translat'; did you mean 'translate'\?\n", result.stderr)
    assert list(tmp_path.iterdir()) == []  # no output folder, no temporary folder


def test_check_reports_each_bad_scene_and_exits_2():
    good, bad = str(TUTORIAL), str(FIXTURES / "unknown_robot_type.scene.yaml")
    result = morsec("check", good, bad)
    assert result.returncode == 2
    assert result.stdout == f"ok: {good}\n"
    assert re.fullmatch(r"error: .*:4:11: robots\[0\]\.type: unknown robot type 'atrvv'; did you mean 'atrv'\?\n",
                        result.stderr)


# ---------------------------------------------------------------- more messages, written inline

def write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


@pytest.mark.parametrize("name, text, line, column, message", [
    ("first_problem.yaml", """\
        robots:
          - type: atrv
            properties: {NoGravity: maybe}
            mass: heavy
            collision: 3
        """, 3, 29, r"robots\[0\]\.properties\.NoGravity: must be true or false, got the string 'maybe' \(and 2 more problems\)"),
    ("mapping_for_list.yaml", "robots:\n  type: atrv\n", 2, 3, r"robots: must be a list, got a mapping"),
    ("list_for_mapping.yaml", "environment: [empty]\n", 1, 14, r"environment: must be a mapping \(key: value\), got a list \['empty'\]"),
    ("missing_type.yaml", "robots:\n  - name: robot\n", 2, 5, r"robots\[0\]: missing key 'type': the robot's catalogue id, e.g. 'atrv'"),
    ("builder_name_typo.yaml", "robots:\n  - type: ATRVV\n", 2, 11, r"robots\[0\]\.type: unknown robot type 'ATRVV'; did you mean 'ATRV'\?"),
    ("no_levels.yaml", "robots:\n  - type: atrv\n    components: [{type: pose, level: raw}]\n", 3, 38,
     r"robots\[0\]\.components\[0\]\.level: component type 'pose' has no levels; remove 'level'"),
    ("object_type.yaml", "objects:\n  - type: boxx\n", 2, 11,
     rf"objects\[0\]\.type: unknown object type 'boxx' \(known: {NAMES}\); did you mean 'box'\?"),
    ("stream_middleware.yaml", "robots:\n  - type: atrv\n    components: [{type: pose, streams: [sockett]}]\n", 3, 41,
     r"robots\[0\]\.components\[0\]\.streams\[0\]: 'sockett' is not one of 'ros', 'socket' or 'text'; did you mean 'socket'\?"),
    ("property_value.yaml", "robots:\n  - type: atrv\n    components:\n      - type: motion_vw\n"
     "        properties: {ControlType: Speed}\n", 5, 35,
     r"robots\[0\]\.components\[0\]\.properties\.ControlType: 'Speed' is not one of 'Velocity' or 'Position'"),
    ("empty_name.yaml", "robots:\n  - {name: '', type: atrv}\n", 2, 12, r"robots\[0\]\.name: a name cannot be empty"),
    ("robot_vs_object.yaml", "robots:\n  - {name: thing, type: atrv}\nobjects:\n  - {name: thing, type: box}\n", 4, 12,
     r"objects\[0\]\.name: duplicate name 'thing': robots and objects share one namespace; rename one of them"),
    ("duplicate_key.yaml", "environment:\n  name: empty\n  name: sandbox\n", 3, 3,
     r"environment\.name: duplicate key 'name': each key may appear once in a mapping"),
    ("python_tag.yaml", "robots:\n  - type: !!python/name:os.system\n", 2, 11,
     r"YAML error: could not determine a constructor for the tag 'tag:yaml\.org,2002:python/name:os\.system'"),
    ("two_documents.yaml", "robots: []\n---\nrobots: []\n", 2, 1,
     r"YAML syntax error: expected a single document in the stream, but found another document"),
    ("not_a_mapping.yaml", "- type: atrv\n", 1, 1,
     r"a scene must be a mapping with environment, robots, objects and zones, got a list \[\{'type': 'atrv'\}\]"),
    ("unknown_modifier.yaml", "robots:\n  - type: atrv\n    components: [{type: pose, modifiers: [{name: nois}]}]\n", 3, 50,
     r"robots\[0\]\.components\[0\]\.modifiers\[0\]\.name: unknown modifier 'nois'; did you mean one of .*\?"),
    ("multinode.yaml", "robots: [{type: atrv}]\nenvironment:\n  multinode: {distribution: {node1: [atrv, ghost]}}\n", 3, 44,
     r"environment\.multinode\.distribution\.node1\[1\]: multinode node 'node1' lists robot 'ghost', which is not in the scene"),
    ("multinode_unassigned.yaml", "robots: [{name: a, type: atrv}, {name: b, type: atrv}]\nenvironment:\n  multinode: {distribution: {n1: [a]}}\n", 3, 29,
     r"environment\.multinode\.distribution: robot 'b' is on no node: list each robot under the node that simulates it \(nodes: n1\)"),
    ("multinode_twice.yaml", "robots: [{name: a, type: atrv}]\nenvironment:\n  multinode: {distribution: {n1: [a], n2: [a]}}\n", 3, 44,
     r"environment\.multinode\.distribution\.n2\[0\]: robot 'a' is on two nodes, 'n1' and 'n2': each robot is simulated by one node"),
    ("multinode_hla.yaml", "robots: [{name: a, type: atrv}]\nenvironment:\n  multinode: {protocol: hla, distribution: {n1: [a]}}\n", 3, 25,
     r"environment\.multinode\.protocol: protocol 'hla' needs an HLA run-time infrastructure \(CERTI with PyHLA\), which cannot be installed here; use protocol 'socket' \(the default\) with `morsec multinode-server`"),
    ("toml_table_key.toml", "[environment.time]\nfrequency = 60\nsteps = 3\n", 3, 1,
     r"environment\.time\.steps: unknown key 'steps'; allowed keys: .*"),
    ("toml_dotted_key.toml", "[environment]\ntime.frequncy = 60\n", 2, 6,
     r"environment\.time\.frequncy: unknown key 'frequncy'; did you mean 'frequency'\?"),
    ("toml_nested_tables.toml", '[[robots]]\ntype = "atrv"\n[[robots.components]]\ntype = "pose"\n'
     '[[robots.components.components]]\ntype = "odometry"\nlevel = "integrate"\n', 7, 9,
     r"robots\[0\]\.components\[0\]\.components\[0\]\.level: unknown level 'integrate' of component type 'odometry' "
     r"\(levels: .*\); did you mean 'integrated'\?"),
    ("toml_sub_table.toml", '[[robots]]\ntype = "atrv"\n[[robots]]\ntype = "rmax"\n[robots.properties]\nNoGravity = 2\n',
     6, 13, r"robots\[1\]\.properties\.NoGravity: must be true or false, got the number 2"),
    ("toml_multiline_array.toml", '[[robots]]\ntype = "atrv"\ntranslate = [\n  0.0,  # x\n  "y",\n  0.0,\n]\n', 5, 3,
     r"robots\[0\]\.translate\[1\]: must be a number, got the string 'y'"),
    ("toml_duplicate_key.toml", '[environment]\nname = "empty"\nname = "sandbox"\n', 3, 17,
     r"TOML syntax error: Cannot overwrite a value \(a key is written twice\)"),
])
def test_error(tmp_path, name, text, line, column, message):
    path = write(tmp_path, name, text)
    assert_error(scene_error(path), path, line, column, message)


def test_yaml_merge_keys_are_followed(tmp_path):
    path = write(tmp_path, "merge.yaml", """\
        robots:
          - &base {type: atrv, name: first, translate: [0, 0, 0]}
          - {<<: *base, name: second, translat: [1, 0, 0]}
        """)
    assert_error(scene_error(path), path, 3, 31, r"robots\[1\]\.translat: unknown key 'translat'; did you mean 'translate'\?")


def test_missing_scene_file(tmp_path):
    result = morsec("build", str(tmp_path / "nope.yaml"), "-o", str(tmp_path / "out"))
    assert result.returncode == 2
    assert result.stderr == f"error: {tmp_path / 'nope.yaml'}: no such scene file\n"
    assert list(tmp_path.iterdir()) == []


# ---------------------------------------------------------------- errors found while compiling

XACRO_OK = """\
<?xml version="1.0"?>
<robot name="$(arg name)" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="name" default="r"/>
  <link name="base_link">
    <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><geometry><box size="{size}"/></geometry></collision>
  </link>
</robot>
"""


def robot_folder(root: Path, cid: str, xacro: str, xacro_text: str | None) -> None:
    folder = root / "robots" / cid
    folder.mkdir(parents=True)
    (folder / "component.py").write_text(textwrap.dedent(f"""\
        from morsec.component import Robot


        class TestRobot(Robot):
            \"\"\"A robot made for the error tests.\"\"\"

            short_descr = "test robot"
            xacro = {xacro!r}


        COMPONENT = TestRobot
        """))
    if xacro_text is not None:
        (folder / xacro).write_text(xacro_text)


@pytest.fixture
def project(tmp_path, monkeypatch) -> Path:
    """A component folder with two broken robots, registered through $MORSEC_COMPONENTS."""
    root = tmp_path / "my_components"
    robot_folder(root, "no_xacro", "missing.urdf.xacro", None)
    robot_folder(root, "flat", "robot.urdf.xacro", XACRO_OK.replace("{size}", "1 -1 1"))
    monkeypatch.setenv("MORSEC_COMPONENTS", str(root))
    return root


def test_missing_xacro_lists_the_path_searched(tmp_path, project):
    scene = write(tmp_path, "scene.yaml", "robots:\n  - {name: r, type: atrv}\n  - name: mine\n    type: no_xacro\n")
    err = scene_error(scene, compile=True)
    searched = project / "robots" / "no_xacro" / "missing.urdf.xacro"
    assert_error(err, scene, 4, 11, rf"robots\[1\]\.type: robot type 'no_xacro': xacro file 'missing\.urdf\.xacro' "
                                   rf"not found \(searched {re.escape(str(searched))}\)")

    out = tmp_path / "out"
    result = morsec("build", str(scene), "-o", str(out), env={"MORSEC_COMPONENTS": str(project)})
    assert result.returncode == 2, result.stderr
    assert result.stderr == f"error: {err}\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["my_components", "scene.yaml"]


def test_scene_mujoco_rejects_is_anchored_to_the_robot(tmp_path, project):
    scene = write(tmp_path, "scene.yaml", """\
        robots:
          - {name: fine, type: atrv}
          - name: bad
            type: flat
        """)
    err = scene_error(scene, compile=True)
    assert_error(err, scene, 3, 5,
                 r"robots\[1\]: MuJoCo rejected the compiled scene \(from 'bad'\): size 1 must be positive in geom")
    result = morsec("check", str(scene), env={"MORSEC_COMPONENTS": str(project)})
    assert (result.returncode, result.stderr) == (2, f"error: {err}\n")


# ---------------------------------------------------------------- the build folder: whole or untouched

def test_failed_build_keeps_the_previous_build(tmp_path, project):
    out = tmp_path / "out"
    good = write(tmp_path, "scene.yaml", "robots:\n  - {name: r, type: atrv}\n")
    build_scene(good, out)
    before = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}
    bad = write(tmp_path, "scene.yaml", "robots:\n  - {name: r, type: flat}\n")
    with pytest.raises(SceneError, match=r"^.*scene\.yaml:2:5: robots\[0\]: MuJoCo rejected"):
        build_scene(bad, out)
    after = {p.relative_to(out): p.read_bytes() for p in out.rglob("*") if p.is_file()}
    assert after == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["my_components", "out", "scene.yaml"]


def test_a_folder_that_is_not_a_build_is_not_replaced(tmp_path):
    out = tmp_path / "precious"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    result = morsec("build", str(TUTORIAL), "-o", str(out))
    assert result.returncode == 2
    assert re.fullmatch(rf"error: {re.escape(str(out))}: refusing to replace a folder that is not a morsec build "
                        r"\(no manifest\.json\); choose another build folder with -o\n", result.stderr)
    assert [p.name for p in out.iterdir()] == ["notes.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["precious"]


def test_a_file_is_not_a_build_folder(tmp_path):
    out = tmp_path / "file"
    out.write_text("mine")
    result = morsec("build", str(TUTORIAL), "-o", str(out))
    assert (result.returncode, result.stderr) == (2, f"error: {out}: exists and is not a folder; "
                                                     "choose another build folder with -o\n")
    assert out.read_text() == "mine"


def test_rebuild_replaces_a_previous_build(tmp_path):
    out = tmp_path / "out"
    build_scene(TUTORIAL, out)
    (out / "stale.txt").write_text("from an older build")
    build_scene(TUTORIAL, out)
    assert not (out / "stale.txt").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]


# ---------------------------------------------------------------- names cannot inject into XML

ODD_NAMES = {"robot": 'r<&"x\'>', "component": "p<&\"]]>", "object": "b&amp;<", "zone": "z\"'"}
XACRO_LOOKALIKE = "${1+1}$(env_HOME)"  # xacro substitutions, which must stay text
q = json.dumps  # a JSON string is a YAML double-quoted string


@pytest.fixture
def odd_build(tmp_path) -> Path:
    scene = write(tmp_path, "names.yaml", f"""\
        robots:
          - name: {q(ODD_NAMES['robot'])}
            type: atrv
            components:
              - {{name: {q(ODD_NAMES['component'])}, type: pose, streams: [socket]}}
          - name: {q(XACRO_LOOKALIKE)}
            type: pioneer3dx
        objects:
          - {{name: {q(ODD_NAMES['object'])}, type: box}}
        zones:
          - {{name: {q(ODD_NAMES['zone'])}, type: Charging}}
        """)
    out = tmp_path / "out"
    build_scene(scene, out)
    return out


def test_xml_special_characters_in_names_round_trip(odd_build):
    root = ET.parse(odd_build / "scene.xml").getroot()
    body_names = {b.get("name") for b in root.iter("body")}
    assert ODD_NAMES["robot"] in body_names
    assert f"{ODD_NAMES['robot']}.{ODD_NAMES['component']}" in body_names
    assert ODD_NAMES["object"] in body_names
    assert XACRO_LOOKALIKE in body_names
    model = mujoco.MjModel.from_xml_path(str(odd_build / "scene.xml"))
    assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, ODD_NAMES["robot"]) >= 0
    for name in (ODD_NAMES["robot"], XACRO_LOOKALIKE):
        urdf = odd_build / "robots" / f"{name}.urdf"
        assert ET.parse(urdf).getroot().get("name") == name  # xacro did not evaluate $(...) or ${...}


def test_urdf_with_odd_names_passes_check_urdf(odd_build):
    assert shutil.which("check_urdf"), "check_urdf (liburdfdom-tools) is required: apt-get install liburdfdom-tools"
    for name in (ODD_NAMES["robot"], XACRO_LOOKALIKE):
        result = subprocess.run(["check_urdf", str(odd_build / "robots" / f"{name}.urdf")],
                                capture_output=True, text=True, timeout=60)
        assert result.returncode == 0, result.stdout + result.stderr
        assert f"robot name is: {name}\n" in result.stdout
