"""Middlewares are registered, never listed: socket and text come through the `morsec.middlewares` entry points,
and a package that registers its own middleware the same way is usable in scenes, builds and runs."""

import json
import os
import subprocess
import textwrap

from runtime_helpers import MORSEC, robot, scene, scene_file

from morsec.middleware.registry import middlewares

RECORDER = '''
"""A third-party middleware: every sensor message appended as a JSON line to one file per stream."""
import json
from pathlib import Path

from pydantic import BaseModel, Field

from morsec.middleware.base import Middleware


class Recorder(Middleware):
    name = "recorder"

    class Options(BaseModel):
        label: str | None = Field(None, description="recorder: the file's name (default: the component's)")

    @classmethod
    def assign(cls, streams):
        return [{"file": f"{s.options.get('label') or s.component}.jsonl"} for s in streams]

    def __init__(self, context, settings):
        super().__init__(context, settings)
        self.files = []

    def open_stream(self, component, direction, endpoint):
        stream = Written(component, Path(self.context.output_dir) / endpoint["file"])
        self.files.append(stream)
        return stream

    def describe(self):
        return [(f.component, "OUT", str(f.path)) for f in self.files]

    def close(self):
        for f in self.files:
            f.close()


class Written:
    listening = True

    def __init__(self, component, path):
        self.component = component
        self.path = path
        self.file = open(path, "w")

    def publish(self, message):
        self.file.write(json.dumps(message) + "\\n")

    def close(self):
        self.file.close()
'''


def test_the_builtin_middlewares_are_registered_entry_points():
    assert {"socket", "text"} <= set(middlewares())
    assert middlewares()["socket"].carries_services and not middlewares()["text"].carries_services


def test_an_option_another_middleware_reads_is_a_located_error(tmp_path):
    pose = {"name": "pose", "type": "pose", "streams": [{"middleware": "text", "port": 5000}]}
    path = scene_file(tmp_path, scene(robot("robot", pose)))
    result = subprocess.run([str(MORSEC), "check", str(path)], capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    line = result.stderr.strip()
    assert line.startswith(f"error: {path}:") and line.count("\n") == 0, line
    assert "robots[0].components[0].streams[0].port: text streams have no option 'port' (they take: file, format)" \
        in line


def test_a_package_registers_its_own_middleware_through_the_same_entry_points(tmp_path):
    site = tmp_path / "site"
    (site / "morsec_recorder-1.0.dist-info").mkdir(parents=True)
    (site / "morsec_recorder-1.0.dist-info" / "METADATA").write_text(
        "Metadata-Version: 2.1\nName: morsec-recorder\nVersion: 1.0\n")
    (site / "morsec_recorder-1.0.dist-info" / "entry_points.txt").write_text(
        "[morsec.middlewares]\nrecorder = recorder_mw:Recorder\n")
    (site / "recorder_mw.py").write_text(textwrap.dedent(RECORDER))
    pose = {"name": "pose", "type": "pose", "streams": [{"middleware": "recorder", "label": "trace"}]}
    path = scene_file(tmp_path, scene(robot("robot", pose)))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(site), os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run([str(MORSEC), "run", str(path), "-o", str(tmp_path / "build"), "--duration", "0.5",
                          "--port-base", "0", "--service-port", "0"],
                         capture_output=True, text=True, timeout=120, cwd=tmp_path, env=env)
    assert run.returncode == 0, run.stderr
    assert f"  robot.pose  OUT  recorder  {tmp_path / 'trace.jsonl'}" in run.stdout
    lines = (tmp_path / "trace.jsonl").read_text().splitlines()
    assert len(lines) >= 25 and set(json.loads(lines[-1])) >= {"timestamp", "x", "y", "z", "yaw"}
    manifest = json.loads((tmp_path / "build" / "manifest.json").read_text())
    assert manifest["streams"] == [{"component": "robot.pose", "direction": "OUT", "middleware": "recorder",
                                    "endpoint": {"file": "trace.jsonl"}}]
    # without the package, the same scene names a middleware that does not exist
    plain = scene_file(tmp_path, scene(robot("robot", {"name": "pose", "type": "pose", "streams": ["recorder"]})),
                       name="plain")
    check = subprocess.run([str(MORSEC), "check", str(plain)], capture_output=True, text=True, timeout=120)
    assert check.returncode == 2 and "'recorder'" in check.stderr and "did you mean" not in check.stderr
