"""The build folder is the contract between compiler and runtime: `morsec run BUILD` decides nothing again,
finds a project's own components from any directory, and refuses a manifest it cannot trust in one line."""

import json
import subprocess
from pathlib import Path

from runtime_helpers import MORSEC, Morsec, build_folder, robot, scene, scene_file

PROBE = '''
from morsec.component import ComponentProperties, DataField, Sensor
from pydantic import Field


class Probe(Sensor):
    """A project's own sensor: reports its Reading property."""

    class Properties(ComponentProperties):
        Reading: float = Field(42.0, description="the value it reports")

    data = (DataField("value", 0.0, "float", "the reading"),)

    def default_action(self):
        self.local_data["value"] = self.properties.Reading


COMPONENT = Probe
'''


def project(tmp_path: Path) -> Path:
    root = tmp_path / "lab"
    (root / "components" / "sensors" / "probe").mkdir(parents=True)
    (root / "morsec.toml").write_text('[project]\nname = "lab"\ncomponents = ["components"]\n')
    (root / "components" / "sensors" / "probe" / "component.py").write_text(PROBE)
    return root


def test_a_build_runs_from_any_directory_with_the_project_components_it_was_built_with(tmp_path):
    root = project(tmp_path)
    probe = {"name": "probe", "type": "probe", "properties": {"Reading": 7.5}, "streams": ["socket"],
             "services": ["socket"]}
    source = scene_file(root, scene(robot("robot", probe)))
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    build = build_folder(source, root / "build" / "scene")
    manifest = json.loads((build / "manifest.json").read_text())
    ref = next(c["component"] for c in manifest["components"] if c["fqn"] == "robot.probe")
    assert ref == {"root": str((root / "components").resolve()), "kind": "sensors", "id": "probe", "name": "Probe",
                   "module": None}
    with Morsec(build, tmp_path, cwd=elsewhere) as sim:  # no morsec.toml above `elsewhere`
        with sim.client() as client:
            assert client.ok("robot.probe", "get_properties") == {"Reading": 7.5}
            client.ok("time", "sleep", 0.1)
            assert client.ok("robot.probe", "get_local_data")["value"] == 7.5


def test_the_runtime_takes_ports_and_modifier_parameters_from_the_manifest(tmp_path):
    """Edit the build: the runtime obeys what the manifest says, it does not recompute it from the scene."""
    source = scene_file(tmp_path, scene(robot("robot", {"name": "pose", "type": "pose", "streams": ["socket"]})))
    build = build_folder(source, tmp_path / "build")
    manifest = json.loads((build / "manifest.json").read_text())
    [stream] = manifest["streams"]
    stream["endpoint"]["port"] = 60123
    stream["endpoint"]["explicit_port"] = True  # kept whatever --port-base says
    (build / "manifest.json").write_text(json.dumps(manifest))
    with Morsec(build, tmp_path) as sim:
        pass
    assert sim.streams["robot.pose"] == ("OUT", 60123), sim.output()


def test_a_manifest_that_breaks_the_contract_is_one_line_and_exit_1(tmp_path):
    source = scene_file(tmp_path, scene(robot("robot")))
    build = build_folder(source, tmp_path / "build")
    manifest = json.loads((build / "manifest.json").read_text())
    manifest["streams"] = [{"component": "robot.pose", "middleware": "socket"}]
    (build / "manifest.json").write_text(json.dumps(manifest))
    result = subprocess.run([str(MORSEC), "run", str(build), "--duration", "0.1"], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 1
    assert result.stderr.strip().count("\n") == 0, result.stderr
    assert "manifest.json: streams.0.direction: Field required; rebuild it (morsec build)" in result.stderr


def test_modifier_parameters_are_resolved_at_build_with_the_environments_defaults(tmp_path):
    """The UTM offsets a scene leaves out come from its environment properties, decided once at build."""
    from morsec.app.project import build_scene
    from morsec.scene.manifest import load_manifest
    pose = {"name": "pose", "type": "pose", "modifiers": [{"name": "utm", "x_offset": 5.0}]}
    content = scene(robot("robot", pose))
    content["environment"]["properties"] = {"UTMXOffset": 100.0, "UTMYOffset": 200.0}
    build = build_scene(scene_file(tmp_path, content), tmp_path / "build")
    [modifier] = next(c for c in load_manifest(build).components if c.fqn == "robot.pose").modifiers
    assert modifier.cls == "morsec.modifiers.coordinates:ToUTM"
    assert (modifier.params["x_offset"], modifier.params["y_offset"], modifier.params["z_offset"]) == (5.0, 200.0, 0.0)
