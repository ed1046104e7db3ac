"""The sweep file and what is made of it before anything runs: its model (YAML and TOML, one located line per
mistake, exit 2), scene paths, the variants and their ids, the metrics' checks, the table, the summary, the
metrics computed from stream files. The runs themselves: tests/test_sweep_runs.py."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pyarrow.parquet as pq
import pytest

from morsec.app.sweep import metrics
from morsec.app.sweep.driver import require
from morsec.app.sweep.execute import client_metrics
from morsec.app.sweep.paths import PathError, parse_path, set_value
from morsec.app.sweep.plan import plan, variants_of
from morsec.app.sweep.spec import load_sweep
from morsec.app.sweep.summary import format_summary, summarize
from morsec.app.sweep.table import CSV, PARQUET, Table
from morsec.errors import MorsecError

ROOT = Path(__file__).resolve().parent.parent
SCENE = (ROOT / "scenes" / "tutorial.yaml").read_text(encoding="utf-8")


@pytest.fixture
def folder(tmp_path) -> Path:
    (tmp_path / "scene.yaml").write_text(SCENE, encoding="utf-8")
    return tmp_path


def sweep_file(folder: Path, text: str, name: str = "sweep.yaml") -> Path:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


def error_of(path: Path, build: bool = False) -> str:
    with pytest.raises(MorsecError) as info:
        sweep = load_sweep(path)
        if build:
            plan(sweep, path.parent / "out")
    return str(info.value)


def test_a_sweep_file_reads_in_yaml_and_toml_alike(folder):
    yaml_path = sweep_file(folder, """\
scene: scene.yaml
duration: 2.5
seeds: 3
grid:
  robots[robot].translate: [[0, 0, 0], [1, 0, 0]]
variants:
  - {environment.gravity: 9.81}
  - {environment.gravity: 3.7}
client: python3 drive.py
metrics: [{robot: robot, zones: [Charging]}]
""")
    toml_path = sweep_file(folder, """\
scene = "scene.yaml"
duration = 2.5
seeds = 3
client = "python3 drive.py"
variants = [{"environment.gravity" = 9.81}, {"environment.gravity" = 3.7}]

[grid]
"robots[robot].translate" = [[0, 0, 0], [1, 0, 0]]

[[metrics]]
robot = "robot"
zones = ["Charging"]
""", "sweep.toml")
    a, b = load_sweep(yaml_path), load_sweep(toml_path)
    assert a.spec == b.spec
    assert a.spec.seeds == [0, 1, 2] and a.scene == folder / "scene.yaml"
    variants = variants_of(a)
    assert [v.values for v in variants] == [
        {"environment.gravity": 9.81, "robots[robot].translate": [0, 0, 0]},
        {"environment.gravity": 9.81, "robots[robot].translate": [1, 0, 0]},
        {"environment.gravity": 3.7, "robots[robot].translate": [0, 0, 0]},
        {"environment.gravity": 3.7, "robots[robot].translate": [1, 0, 0]}]
    assert [v.id for v in variants] == [v.id for v in variants_of(b)]


def test_a_variant_is_named_by_its_values_and_equal_variants_are_one(folder):
    sweep = load_sweep(sweep_file(folder, """\
scene: scene.yaml
duration: 1
variants:
  - {environment.gravity: 9.81, "robots[robot].translate": [0, 0, 0]}
  - {"robots[robot].translate": [0, 0, 0], environment.gravity: 9.81}
  - {environment.gravity: 1.0}
"""))
    variants = variants_of(sweep)
    assert len(variants) == 2
    assert variants[0].id != variants[1].id and variants[0].id.startswith("v")


@pytest.mark.parametrize(("text", "expected"), [
    ("scene: scene.yaml\nduraton: 2\n", "sweep.yaml:2:1: duraton: unknown key 'duraton'; did you mean 'duration'?"),
    ("scene: scene.yaml\n", "sweep.yaml:1:1: missing required key 'duration'"),
    ("scene: scene.yaml\nduration: -1\n", "sweep.yaml:2:11: duration: must be greater than 0, got -1"),
    ("scene: scene.yaml\nduration: 1\nseeds: [1, 2, 1]\n", "sweep.yaml:3:8: seeds: seed 1 is listed twice"),
    ("scene: scene.yaml\nduration: 1\nseeds: 0\n", "sweep.yaml:3:8: seeds: a number of seeds must be 1 or more, got 0"),
    ("scene: scene.yaml\nduration: 1\ngrid: {environment.gravity: []}\n",
     "sweep.yaml:3:29: grid.environment.gravity: must have at least 1 items, got 0"),
    ("scene: scene.yaml\nduration: 1\nmetrics: [{robot: robot, zone: [x]}]\n",
     "sweep.yaml:3:26: metrics[0].zone: unknown key 'zone'; did you mean 'zones'?"),
    ("- scene.yaml\n", "sweep.yaml:1:1: a sweep must be a mapping with scene, duration, seeds, grid or variants, client "
                       "and metrics, got a list ['scene.yaml']"),
    ("scene: [scene.yaml\n", "sweep.yaml:2:1: YAML syntax error"),
])
def test_a_mistake_in_the_sweep_file_is_one_located_line(folder, text, expected):
    message = error_of(sweep_file(folder, text))
    assert message.startswith(str(folder / expected)), message


@pytest.mark.parametrize(("lines", "expected"), [
    ("grid:\n  robots[robt].translate: [[0, 0, 0]]\n",
     "sweep.yaml:4:3: grid.robots[robt].translate: robots has no item named 'robt'; did you mean 'robot'?"),
    ("grid:\n  robots[robot].translate: [[0, 0, 0], [1, 2]]\n",
     "sweep.yaml:4:40: grid.robots[robot].translate[1]: [1, 2] makes the scene invalid: robots[0].translate: must be a "
     "list of 3 numbers [x, y, z], got 2: [1, 2]"),
    ("variants:\n  - robots[robot].components[motion].properties.speeed: 1\n",
     "sweep.yaml:4:57: variants[0].robots[robot].components[motion].properties.speeed: 1 makes the scene invalid: "
     "robots[0].components[1].properties.speeed: unknown property 'speeed' of actuator type 'motion_vw' (properties: "
     "'ControlType')"),
    ("grid:\n  robots[robot]..translate: [[0, 0, 0]]\n",
     "sweep.yaml:4:3: grid.robots[robot]..translate: not a scene path: cannot read '..translate'"),
    ("grid:\n  robots[3].translate: [[0, 0, 0]]\n", "sweep.yaml:4:3: grid.robots[3].translate: robots has 1 items, no "
                                                   "item 3"),
    ("grid:\n  environment.gravity.x: [1]\n", "sweep.yaml:4:3: grid.environment.gravity.x: environment.gravity is the "
                                             "value 9.81, not a mapping: no key 'x' in it"),
    ("grid:\n  environment.gravity: [1]\nvariants:\n  - {environment.gravity: 2}\n",
     "sweep.yaml:6:6: variants[0].environment.gravity: 'environment.gravity' is also in grid"),
    ("metrics:\n  - robot: robat\n", "sweep.yaml:4:12: metrics[0].robot: the scene has no robot 'robat'; did you "
                                     "mean 'robot'?"),
    ("metrics:\n  - {robot: robot, pose: motion}\n", "sweep.yaml:4:26: metrics[0].pose: robot.motion is a 'motion_vw', "
                                                     "not a pose sensor"),
    ("metrics:\n  - {robot: robot, zones: [Charge]}\n", "sweep.yaml:4:28: metrics[0].zones[0]: the scene has no zone "
                                                        "'Charge'; did you mean 'Charging'?"),
])
def test_what_the_scene_refuses_is_reported_at_the_sweeps_value(folder, lines, expected):
    message = error_of(sweep_file(folder, "scene: scene.yaml\nduration: 1\n" + lines), build=True)
    assert message.startswith(str(folder / expected)), message


def test_a_sweep_of_a_missing_scene_or_a_builder_script_is_refused(folder):
    assert error_of(sweep_file(folder, "scene: nope.yaml\nduration: 1\n"), build=True) == \
        f"{folder / 'sweep.yaml'}:1:8: scene: no such scene file {str(folder / 'nope.yaml')!r}"
    (folder / "scene.py").write_text("from morse.builder import *\nrobot = ATRV()\n", encoding="utf-8")
    assert "a sweep's scene is a YAML or TOML file (a builder script converts to one: morsec convert scene.py -o " \
           "scene.yaml)" in error_of(sweep_file(folder, "scene: scene.py\nduration: 1\n"), build=True)


def test_a_scene_that_is_wrong_by_itself_is_reported_in_the_scene(folder):
    (folder / "scene.yaml").write_text(SCENE.replace("type: atrv", "type: atrvv"), encoding="utf-8")
    message = error_of(sweep_file(folder, "scene: scene.yaml\nduration: 1\ngrid: {environment.gravity: [1]}\n"),
                       build=True)
    assert message.startswith(f"{folder / 'scene.yaml'}:") and "unknown robot type 'atrvv'" in message


def test_morsec_sweep_says_a_mistake_in_one_line_with_exit_2(folder):
    path = sweep_file(folder, "scene: scene.yaml\nduration: 1\nseeds: [a]\n")
    result = subprocess.run([sys.executable, "-m", "morsec", "sweep", str(path), "-o", str(folder / "out")],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    assert result.stderr == f"error: {path}:3:9: seeds[0]: must be an integer, got the string 'a'\n"


def test_a_missing_dependency_is_named_with_its_install_line():
    with pytest.raises(MorsecError) as info:
        require("no_such_module_for_morsec", "no_such_module_for_morsec (--frobnicate)")
    assert str(info.value) == ("morsec sweep needs no_such_module_for_morsec (--frobnicate), which is not installed: "
                               "pip install 'morsec[sweep]'")


def test_equal_variants_build_once_and_builds_are_reused(folder):
    sweep = load_sweep(sweep_file(folder, """\
scene: scene.yaml
duration: 1
seeds: [0, 1]
grid:
  robots[robot].translate: [[0, 0, 0], [1, 0, 0]]
metrics: [{robot: robot}]
"""))
    variants, tasks = plan(sweep, folder / "out")
    assert len(tasks) == 4 and len({t.run for t in tasks}) == 4
    assert len({v.build for v in variants}) == 2
    manifest = json.loads((variants[1].build / "manifest.json").read_text())
    assert manifest["scene"]["robots"][0]["translate"] == [1.0, 0.0, 0.0]
    assert manifest["scene"]["environment"]["time"]["relative"] is True
    fqns = {c["fqn"] for c in manifest["components"]}
    assert {"robot.sweep_pose", "robot.sweep_collision"} <= fqns
    stamp = (variants[1].build / "manifest.json").stat().st_mtime_ns
    plan(sweep, folder / "out")
    assert (variants[1].build / "manifest.json").stat().st_mtime_ns == stamp  # not compiled again


def test_scene_paths():
    assert parse_path("robots[robot].components[0].properties.speed") == (
        "robots", ("robot",), "components", 0, "properties", "speed")
    data = {"robots": [{"name": "a", "components": [{"type": "pose"}]}], "zones": [{"type": "Charging"}]}
    assert set_value(data, "robots[a].components[pose].properties.x", 1) == ("robots", 0, "components", 0,
                                                                             "properties", "x")
    assert data["robots"][0]["components"][0]["properties"] == {"x": 1}
    assert set_value(data, "zones[Charging].size", [2, 2, 2]) == ("zones", 0, "size")
    assert set_value(data, "environment.time.frequency", 120) == ("environment", "time", "frequency")
    with pytest.raises(PathError, match="robots has no item named 'b' \\(names: 'a'\\)"):
        set_value(data, "robots[b].translate", [0, 0, 0])
    for bad in ("", "[0].x", "a.", "a[].b", "a[0]x"):
        with pytest.raises(PathError, match="not a scene path"):
            parse_path(bad)


def test_metrics_from_stream_files(tmp_path):
    poses = [{"timestamp": str(t / 10), "x": str(t * 0.5), "y": "0.0", "z": "0.1", "yaw": "0.0"} for t in range(11)]
    points = [(float(p["x"]), 0.0, 0.1) for p in poses]
    zone = {"translate": [3.0, 0.0, 0.0], "size": [2.0, 2.0, 2.0]}
    assert metrics.first_entry(poses, points, zone) == 0.4  # x = 2.0, the zone's edge
    assert metrics.first_entry(poses, points, {"translate": [30.0, 0, 0], "size": [1, 1, 1]}) is None
    touching = [{"timestamp": "1.0", "objects": "crate"}, {"timestamp": "1.1", "objects": "crate,wall"},
                {"timestamp": "1.2", "objects": "wall"}, {"timestamp": "2.0", "objects": "wall"}]
    assert metrics.contacts_begun(touching, 0.1) == 3  # crate, wall, wall again after a gap


def test_client_metrics_are_its_last_line_when_that_is_a_json_object():
    assert client_metrics('starting\n{"a": 1, "ok": true}\n\n') == {"a": 1, "ok": True}
    assert client_metrics('{"a": 1}\ndone\n') == {}
    assert client_metrics("[1, 2]\n") == {} and client_metrics("") == {}


def test_the_table_keeps_types_and_is_read_back_to_resume(tmp_path):
    table = Table(tmp_path, ["p"])
    rows = [{"run": "v1-s0", "variant": "v1", "seed": 0, "p": "[1, 2]", "status": "ok", "reason": "",
             "m": 1, "flag": True, "sim_time": 1.0, "wall_time": 0.5, "rtf": 2.0, "host": "h", "log": "l0"},
            {"run": "v1-s1", "variant": "v1", "seed": 1, "p": "[1, 2]", "status": "client_failed", "reason": "x",
             "m": 0.1 + 0.2, "flag": False, "new": "text", "sim_time": None, "wall_time": 0.5, "rtf": None,
             "host": "h", "log": "l1"}]
    for row in rows:
        table.add(row)
    read = pq.read_table(tmp_path / PARQUET).to_pylist()
    assert read[1]["m"] == 0.1 + 0.2 and read[0]["m"] == 1.0 and read[0]["flag"] is True
    assert read[0]["new"] is None and read[1]["sim_time"] is None
    header = (tmp_path / CSV).read_text().splitlines()[0]
    assert header == "run,variant,seed,p,status,reason,m,flag,new,sim_time,wall_time,rtf,host,log"
    again = Table.resume(tmp_path, ["p"])
    assert again.done() == {"v1-s0", "v1-s1"} and again.rows == read


def test_the_summary_pools_runs_per_parameter_value():
    rows = [{"run": f"r{i}", "status": "ok" if i != 3 else "timed_out", "speed": s, "d": d}
            for i, (s, d) in enumerate([(1, 1.0), (1, 3.0), (2, 4.0), (2, 100.0)])]
    groups = summarize(rows, ["speed"], {"speed": [2, 1]})
    assert [(g.value, g.runs, g.failed) for g in groups] == [(2, 2, 1), (1, 2, 0)]
    assert groups[1].stats["d"].mean == 2.0 and groups[1].stats["d"].std == pytest.approx(2 ** 0.5)
    assert groups[0].stats["d"].n == 1  # the run that timed out does not count
    text = format_summary(groups)
    assert text.splitlines()[0].split() == ["speed", "runs", "failed", "d"]
    assert text.splitlines()[2].split() == ["1", "2", "0", "2", "±", "1.414"]


def test_the_sweeps_page_documents_every_key_and_client_variable():
    from morsec.app.sweep.spec import MetricSpec, SweepSpec
    page = (ROOT / "docs" / "sweeps.md").read_text(encoding="utf-8")
    for model in (SweepSpec, MetricSpec):
        for name in model.model_fields:
            assert f"| `{name}` |" in page, f"docs/sweeps.md does not describe {model.__name__}.{name}"
    execute = (ROOT / "morsec" / "app" / "sweep" / "execute.py").read_text(encoding="utf-8")
    for variable in sorted(set(re.findall(r"\b(MORSEC_[A-Z_]+)\b", execute)) - {"MORSEC_PORT_"}):
        assert f"`{variable}`" in page, f"docs/sweeps.md does not describe {variable}"
    assert "`MORSEC_PORT_<NAME>`" in page
