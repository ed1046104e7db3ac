"""schemas/messages/: the JSON Schema of each stream's message, generated from the data fields, checked in
and fresh; real messages from running sensors validate against them."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import jsonschema
import pytest
from runtime_helpers import read_lines, stream_client

from morsec.app.schemas import MESSAGES_DIR, REGENERATE, message_schema_files
from morsec.component import DataField
from morsec.component.catalogue import load_catalogue
from morsec.component.fields import FIELD_TYPES, type_schema
from morsec.errors import MorsecError
from morsec.testing import simulate

ROOT = Path(__file__).resolve().parent.parent
MESSAGES = ROOT / MESSAGES_DIR


@pytest.fixture(autouse=True)
def _builtin_catalogue(monkeypatch):
    monkeypatch.delenv("MORSEC_COMPONENTS", raising=False)


@pytest.fixture(scope="module")
def fresh() -> dict[str, str]:
    return message_schema_files(load_catalogue(ROOT))


def test_checked_in_message_schemas_are_fresh(fresh):
    checked_in = {p.relative_to(MESSAGES).as_posix() for p in MESSAGES.rglob("*.schema.json")}
    assert checked_in == set(fresh), (f"{MESSAGES_DIR} does not match the catalogue (missing "
                                      f"{sorted(set(fresh) - checked_in)[:5]}, extra {sorted(checked_in - set(fresh))[:5]}): "
                                      f"run `{REGENERATE}` from the repository root")
    stale = [name for name, text in sorted(fresh.items()) if (MESSAGES / name).read_text(encoding="utf-8") != text]
    assert not stale, f"message schemas {stale[:5]} are stale: run `{REGENERATE}` from the repository root"


def test_every_streaming_component_has_a_valid_schema(fresh):
    cat = load_catalogue(ROOT)
    expected = {f"{kind}/{cid}.schema.json" for kind in ("sensors", "actuators") for cid in cat.ids(kind)
                if cat.by_kind[kind][cid].exportable}
    assert set(fresh) == expected
    for name, text in fresh.items():
        schema = json.loads(text)
        jsonschema.Draft202012Validator.check_schema(schema)
        root = schema["$defs"][schema["$ref"].rsplit("/", 1)[-1]] if "$ref" in schema else schema
        if name.startswith("sensors/"):
            assert root["required"][0] == "timestamp", name
            assert list(root["properties"])[0] == "timestamp", name


def test_morsec_schema_messages_writes_them(tmp_path, fresh):
    out = tmp_path / "messages"
    (out / "sensors").mkdir(parents=True)
    (out / "sensors" / "gone.schema.json").write_text("{}")  # a component that no longer exists
    result = subprocess.run([sys.executable, "-c", "from morsec.cli import main; main()", "schema", "--messages",
                             str(out)], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    written = {p.relative_to(out).as_posix(): p.read_text(encoding="utf-8") for p in out.rglob("*.schema.json")}
    assert written == fresh


def test_every_field_type_has_a_schema():
    for name in FIELD_TYPES:
        jsonschema.Draft202012Validator.check_schema(type_schema(name))


def test_a_data_field_of_an_unknown_type_names_the_field():
    with pytest.raises(ValueError, match=r"data field 'speed': type 'double' is not one of .*'float'"):
        DataField("speed", 0.0, "double", "a speed, m/s")


def test_a_component_with_an_unknown_field_type_names_its_file(tmp_path, monkeypatch):
    folder = tmp_path / "components" / "sensors" / "hygro"
    folder.mkdir(parents=True)
    (folder / "component.py").write_text(
        "from morsec.component import DataField, Sensor\n\n\n"
        "class Hygro(Sensor):\n"
        "    data = (DataField('humidity', 0.5, 'percent', 'relative humidity'),)\n\n\n"
        "COMPONENT = Hygro\n")
    monkeypatch.setenv("MORSEC_COMPONENTS", str(tmp_path / "components"))
    with pytest.raises(MorsecError) as err:
        load_catalogue(tmp_path)
    assert str(folder / "component.py") in str(err.value) and "'humidity'" in str(err.value)
    assert "'percent'" in str(err.value)


# ---------------------------------------------------------------- real messages

SCENE = """
robots:
  - name: robot
    type: atrv
    components:
      - {name: motion, type: motion_vw}
      - {name: pose, type: pose, streams: [socket]}
      - {name: odometry, type: odometry, streams: [socket]}
      - {name: diff, type: odometry, level: differential, streams: [socket]}
      - {name: imu, type: imu, streams: [socket]}
      - {name: laser, type: laser_scanner, level: rssi, translate: [0.3, 0, 0.3],
         properties: {resolution: 10.0, scan_window: 180.0}, streams: [socket]}
      - {name: gps, type: gps, level: extended, streams: [socket]}
      - {name: camera, type: video_camera, translate: [0.3, 0, 0.5], properties: {cam_width: 8, cam_height: 6},
         streams: [socket]}
objects:
  - {name: wall, type: box, translate: [3, 0, 0.5], size: [0.2, 4, 1]}
environment:
  name: sandbox
  properties: {longitude: 1.45, latitude: 43.6, altitude: 150.0}
"""
STREAMS = {"robot.pose": ("pose", None), "robot.odometry": ("odometry", None),
           "robot.diff": ("odometry", "differential"), "robot.imu": ("imu", None),
           "robot.laser": ("laser_scanner", "rssi"), "robot.gps": ("gps", "extended"),
           "robot.camera": ("video_camera", None)}



def _validator(cid: str, level: str | None) -> jsonschema.Draft202012Validator:
    schema = json.loads((MESSAGES / "sensors" / f"{cid}.schema.json").read_text(encoding="utf-8"))
    if level is not None:  # one level's message: its definition, in the file that holds it
        schema = {**schema, "$ref": f"#/$defs/{level}"}
    return jsonschema.Draft202012Validator(schema)


def test_stream_messages_of_running_sensors_validate(tmp_path):
    with simulate(SCENE, tmp_path) as sim:
        clients = {fqn: stream_client(sim, fqn) for fqn in STREAMS}
        sim.command("robot.motion", v=0.5, w=0.2)
        sim.run_for(0.5)
        messages = {fqn: json.loads(read_lines(client)[-1]) for fqn, client in clients.items()}
        for client in clients.values():
            client.close()
    for fqn, (cid, level) in STREAMS.items():
        message = messages[fqn]
        errors = list(_validator(cid, level).iter_errors(message))
        assert not errors, f"{fqn}: " + "; ".join(f"{list(e.absolute_path)}: {e.message[:200]}" for e in errors)
        assert list(message)[0] == "timestamp"
    wrong = dict(messages["robot.pose"], x="far")
    assert list(_validator("pose", None).iter_errors(wrong))
    del wrong["x"]
    assert list(_validator("pose", None).iter_errors(wrong))
    assert list(_validator("odometry", "differential").iter_errors(messages["robot.odometry"]))  # another level
