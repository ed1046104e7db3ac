"""The whole flow of issue 6, as a user runs it, in a temporary folder: `morsec create`, two `morsec add`,
both new components used in a scene, build, run, drive with pymorse, and the generated project's own
tests — unedited."""

import math
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from runtime_helpers import Morsec  # noqa: E402

from morsec.pymorse_compat import patch_pymorse  # noqa: E402

MORSEC = Path(sys.executable).with_name("morsec")

SCENE = textwrap.dedent("""\
    environment: {name: empty}          # best_effort: simulated time follows the clock, as for a user
    robots:
      - name: robot
        type: atrv
        default_interface: socket
        components:
          - {name: pose, type: pose, translate: [0.0, 0.0, -0.1]}
          - {name: heat, type: thermal_cam, level: detailed}
          - {name: drive, type: gripper_x}
    objects:
      - {name: stove, type: box, translate: [4.0, 0.0, 0.0], size: [0.3, 0.3, 0.3]}
    """)


def morsec(*args, cwd: Path, stdin: str | None = None) -> subprocess.CompletedProcess:
    result = subprocess.run([str(MORSEC), *args], cwd=cwd, capture_output=True, text=True, timeout=300,
                            input=stdin)
    assert result.returncode == 0, f"morsec {' '.join(args)} failed:\n{result.stdout}\n{result.stderr}"
    return result


def test_create_add_run_drive_and_test(tmp_path):
    morsec("create", "mysim", cwd=tmp_path)
    project = tmp_path / "mysim"
    added = morsec("add", "sensor", "thermal_cam", ".", "--description", "Measures heat", cwd=project)
    assert "type: thermal_cam" in added.stdout and "ThermalCam()" in added.stdout  # how to use it
    morsec("add", "actuator", "gripper_x", ".", cwd=project)  # no terminal: the default description
    listing = morsec("components", cwd=project).stdout
    assert "thermal_cam" in listing and "Measures heat" in listing and "gripper_x" in listing
    schema = morsec("schema", cwd=project).stdout
    assert '"thermal_cam"' in schema and '"GripperX"' in schema
    # the project's own schema file, which its scenes name for editors, follows `add`
    assert (project / "scene.schema.json").read_text() == schema
    assert (project / "scenes/default.yaml").read_text().startswith(
        "# yaml-language-server: $schema=../scene.schema.json")

    check_generated_components_declare_once(project)

    (project / "scenes" / "flow.yaml").write_text(SCENE)
    morsec("build", "scenes/flow.yaml", "-o", "build/flow", cwd=project)
    assert (project / "build/flow/manifest.json").is_file()

    patch_pymorse()
    from pymorse import Morse
    with Morsec(project / "scenes/flow.yaml", project, cwd=project, prebuild=False) as sim:
        with Morse(port=sim.service_port) as client:
            heat = client.robot.heat.get(timeout=10)
            assert heat["nearest"] == "stove"
            assert math.isclose(heat["distance"], 4.0 - 0.0, abs_tol=0.05)  # sensor at the robot's origin
            client.robot.drive.publish({"vx": 1.0, "wz": 0.0})
            client.sleep(2.0)
            pose = client.robot.pose.get(timeout=10)
            assert pose["x"] == pytest.approx(2.0, abs=0.15)
            assert client.robot.heat.get(timeout=10)["distance"] == pytest.approx(2.0, abs=0.2)
            client.robot.drive.stop().result(timeout=10)
            client.quit()

    result = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider"], cwd=project,
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "4 passed" in result.stdout  # the default scene's test and the two components' (the actuator has two)


def check_generated_components_declare_once(project: Path) -> None:
    """The scaffold follows the catalogue's rules: descriptions in code, typed fields (a valid message
    schema), a README of prose without the tables the code declares."""
    import jsonschema
    from test_component_docs import DECLARED_HEADERS, tables

    from morsec.component.catalogue import load_catalogue
    morsec("add", "robot", "rover_x", ".", "--description", "A rover", cwd=project)
    cat = load_catalogue(project)
    for kind, cid in (("sensors", "thermal_cam"), ("actuators", "gripper_x"), ("robots", "rover_x")):
        cls = cat.by_kind[kind][cid]
        assert all(info.description for info in cls.Properties.model_fields.values()), cid
        assert all(f.doc for f in getattr(cls, "data", ())), cid
        for level in [lv.name for lv in getattr(cls, "levels", ())] or [None]:
            if kind != "robots":
                jsonschema.Draft202012Validator.check_schema(cls.message_schema(level))
        readme = (project / "components" / kind / cid / "README.md").read_text(encoding="utf-8")
        for line, header, _ in tables(readme):
            assert not {cell.strip("` ").lower() for cell in header} & DECLARED_HEADERS, (cid, line, header)
    morsec("rm", "robot", "rover_x", ".", "-f", cwd=project)


def test_rm_removes_what_add_generated(tmp_path):
    morsec("create", "p", cwd=tmp_path)
    project = tmp_path / "p"
    before = sorted(str(p.relative_to(project)) for p in project.rglob("*"))
    schema = (project / "scene.schema.json").read_text()
    morsec("add", "sensor", "probe", ".", "--description", "x", cwd=project)
    assert '"probe"' in (project / "scene.schema.json").read_text()
    morsec("rm", "sensor", "probe", ".", "--force", cwd=project)
    assert sorted(str(p.relative_to(project)) for p in project.rglob("*")) == before
    assert (project / "scene.schema.json").read_text() == schema


def test_add_refuses_bad_names_builtins_and_overwrites(tmp_path):
    morsec("create", "p", cwd=tmp_path)
    project = tmp_path / "p"
    for args, message in ((("sensor", "Bad-Name"), "invalid sensor name 'Bad-Name'"),
                          (("sensor", "pose"), "'pose' is a built-in component"),
                          (("widget", "w"), "unknown component kind 'widget'")):
        result = subprocess.run([str(MORSEC), "add", *args, ".", "--description", "x"], cwd=project,
                                capture_output=True, text=True, timeout=120)
        assert result.returncode == 2 and message in result.stderr, result.stderr
    readme = project / "components/sensors/probe/README.md"
    morsec("add", "sensor", "probe", ".", "--description", "Counts photons", cwd=project)
    first = readme.read_text()
    again = subprocess.run([str(MORSEC), "add", "sensor", "probe", ".", "--description", "Weighs boxes"],
                           cwd=project, capture_output=True, text=True, timeout=120)
    assert again.returncode == 2 and "already exists; use --force" in again.stderr
    assert readme.read_text() == first  # refused: nothing was overwritten
    morsec("add", "sensor", "probe", ".", "--description", "Weighs boxes", "--force", cwd=project)
    # the README (templates/scaffold/sensor/README.md.j2) names the component, gives the new description
    # and shows how to use it in a scene and in a builder script
    text = readme.read_text()
    assert text.startswith("# probe\n\nWeighs boxes\n\nGenerated by `morsec add sensor probe`")
    assert "Counts photons" not in text
    assert "- {name: probe, type: probe, level: detailed, streams: [socket]}" in text
    assert "probe = Probe()\nprobe.level('detailed')\nrobot.append(probe)" in text
    assert "{{" not in text and "{%" not in text  # every template variable rendered
    outside = subprocess.run([str(MORSEC), "add", "sensor", "x", str(tmp_path)], capture_output=True, text=True,
                             timeout=120)
    assert outside.returncode == 2 and "not in a morsec project" in outside.stderr
