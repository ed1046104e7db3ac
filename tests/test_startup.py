"""What start-up does not pay for (issue 14): `morsec run` of a build folder imports nothing that only building
needs, nor typer (morsec.cli.run_args reads its command line), and another command assembles only itself; an
up-to-date build is not compiled again, and anything a build is made from, changed, makes it compile. Each
check runs a real `morsec` in a subprocess (a fresh interpreter: what the test process imported does not
count)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from importlib.metadata import entry_points
from pathlib import Path

import pytest

from morsec.app import buildcache
from morsec.app.project import build_scene, prepare_build
from morsec.cli import COMMANDS, command_of
from morsec.cli.assemble import make_app
from morsec.resources import entry_points_of

REPO = Path(__file__).resolve().parent.parent
SCENE = """\
environment: {name: empty, time: {strategy: fixed_step, frequency: 60}}
robots:
  - name: robot
    type: atrv
    components:
      - {name: pose, type: pose, streams: [socket]}
      - {name: motion, type: motion_vw, streams: [socket]}
"""
# what only building needs: the URDF and mesh libraries, templates, YAML, the front ends, the compiler,
# the scene's own models and their validation, rich's terminal output
BUILD_ONLY = ("yourdfpy", "trimesh", "scipy", "networkx", "lxml", "jinja2", "xacro", "yaml", "rich",
              "morsec.frontends", "morsec.frontends.builder", "morsec.compiler", "morsec.scene.models",
              "morsec.scene.validate", "morsec.scene.schema")
# what only `morsec sweep` needs: its engine, its table, its plot
SWEEP_ONLY = ("dask", "distributed", "pandas", "pyarrow", "matplotlib", "morsec.app.sweep")
# what only `morsec run --foxglove` needs: Foxglove's server
FOXGLOVE_ONLY = ("foxglove", "morsec.runtime.foxglove")
# what only a recording needs (`morsec run --record`): MCAP, ROS 2's messages, the recorder
RECORD_ONLY = ("mcap", "rosbags", "morsec.middleware.record", "morsec.app.replay")
# what only a scene with MORSE-API components needs: the emulation of MORSE's core, Blender's mathutils
MORSE_API_ONLY = ("morse", "morse.core", "morse.core.emulation", "morse.helpers", "mathutils")
# what a usual `morsec run` command line does not need (morsec.cli.run_args reads it): typer and its adapters
TYPER_ONLY = ("typer", "morsec.cli.assemble", "morsec.cli.running")

# the middlewares the scene (socket streams only) does not use (morsec.middleware.registry imports one on use)
UNUSED_MIDDLEWARES = ("morsec.middleware.ros", "morsec.middleware.text")

# what only rendering needs: the GL backend (EGL or OSMesa) MuJoCo renders with (kits.render imports it when
# something first renders)
GL_ONLY = ("OpenGL", "mujoco.egl", "mujoco.osmesa")

# `morsec run` with Simulation.announce reporting which of argv[1]'s modules are loaded (and whether the
# collector is on) at SCENE INITIALIZED; the runtime is patched once morsec imports it, so that the test
# imports nothing (MuJoCo above all) before morsec does
AT_SCENE_INITIALIZED = """\
import gc, importlib.machinery, json, sys

def report(announce):
    def announce_and_report(self, out=sys.stdout):
        announce(self, out)
        print("MODULES " + json.dumps({"loaded": sorted(m for m in sys.argv[1].split(",") if m in sys.modules),
                                       "gc": gc.isenabled()}), flush=True)
    return announce_and_report

class PatchSimulation:
    def find_spec(self, name, path, target=None):
        if name != "morsec.runtime.simulation":
            return None
        spec = importlib.machinery.PathFinder.find_spec(name, path)
        run = spec.loader.exec_module
        def exec_module(module):
            run(module)
            module.Simulation.announce = report(module.Simulation.announce)
        spec.loader.exec_module = exec_module
        return spec

sys.meta_path.insert(0, PatchSimulation())
from morsec.cli import main
main(sys.argv[2:])
"""


def run_python(code: str, *args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")]))
    result = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, timeout=120,
                            env=env, cwd=cwd)
    assert result.returncode == 0, result.stderr
    return result


def test_mujoco_imported_for_a_run_loads_its_gl_backend_when_something_first_renders():
    """A run imports MuJoCo without its GL backend (kits.render.import_mujoco_gl_on_first_use); whatever renders
    first (mujoco.Renderer, as the cameras and a lab's own component do; mujoco.GLContext) gets the backend
    morsec chose, and MUJOCO_GL stays as it was for child processes."""
    code = """\
import os, sys
import morsec
chosen = os.environ["MUJOCO_GL"]
from morsec.kits.render import import_mujoco_gl_on_first_use
import_mujoco_gl_on_first_use()
import mujoco
assert os.environ["MUJOCO_GL"] == chosen
assert not any(m in sys.modules for m in ("OpenGL", "mujoco.egl", "mujoco.osmesa")), "GL imported early"
model = mujoco.MjModel.from_xml_string(
    '<mujoco><worldbody><light pos="0 0 3"/><geom type="box" size=".5 .5 .5" rgba="1 0 0 1"/>'
    '<camera name="c" pos="0 0 3"/></worldbody></mujoco>')
data = mujoco.MjData(model)
mujoco.mj_forward(model, data)
renderer = mujoco.Renderer(model, 32, 32)
renderer.update_scene(data, camera="c")
image = renderer.render()
print(chosen, int(image[16, 16, 0]), int(image[16, 16, 1]), mujoco.GLContext.__module__)
"""
    backend, red, green, module = run_python(code).stdout.split()
    assert backend in ("egl", "osmesa") and module == f"mujoco.{backend}"
    assert int(red) > int(green) + 100  # the red box, lit, seen from above (a background would be grey)


@pytest.fixture
def scene(tmp_path) -> Path:
    path = tmp_path / "scene.yaml"
    path.write_text(SCENE, encoding="utf-8")
    return path


def test_running_a_build_imports_nothing_only_building_needs(scene, tmp_path):
    build = build_scene(scene, tmp_path / "build")
    result = run_python(AT_SCENE_INITIALIZED, ",".join(BUILD_ONLY + SWEEP_ONLY + FOXGLOVE_ONLY + RECORD_ONLY
                                                       + MORSE_API_ONLY + TYPER_ONLY + GL_ONLY
                                                       + UNUSED_MIDDLEWARES), "run", str(build),
                        "--duration", "0.05",
                        "--time-strategy", "fixed_step", "--port-base", "0", "--service-port", "0")
    line = next(x for x in result.stdout.splitlines() if x.startswith("MODULES "))
    report = json.loads(line.removeprefix("MODULES "))
    assert report["loaded"] == []
    assert report["gc"], "the garbage collector must be on again once the simulation is initialized"
    assert "SCENE INITIALIZED" in result.stdout and "EXITING SIMULATION" in result.stdout


def test_a_command_line_assembles_its_command_only():
    only_run = make_app(command_of(["run", "build/x", "--duration", "1"]))
    assert [c.callback.__name__ for c in only_run.registered_commands] == ["run", "version"]
    everything = make_app(command_of(["--help"]))
    assert [c.name or c.callback.__name__ for c in everything.registered_commands] == [*COMMANDS, "version"]
    assert command_of(["bogus"]) is None and command_of([]) is None


def test_help_still_lists_every_command():
    result = run_python("from morsec.cli import main; main(['--help'])")
    for name in COMMANDS:
        assert name in result.stdout


def test_an_unchanged_scene_is_not_compiled_again(scene, tmp_path):
    out = tmp_path / "build"
    build_scene(scene, out)
    before = {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    code = ("import sys\nfrom pathlib import Path\nfrom morsec.app.project import build_scene\n"
            "build_scene(Path(sys.argv[1]), Path(sys.argv[2]))\n"
            "print(sorted(m for m in ('morsec.compiler', 'morsec.frontends', 'mujoco', 'pydantic') "
            "if m in sys.modules))")
    assert run_python(code, str(scene), str(out)).stdout.strip() == "[]"
    assert {p: p.read_bytes() for p in out.rglob("*") if p.is_file()} == before


def compiled(scene: Path, out: Path, run: bool = False) -> bool:
    """Whether building `scene` into `out` (as `morsec build`, or as `morsec run` of the scene) compiled it."""
    import morsec.compiler.build as compiler
    calls = []
    original = compiler.compile_scene
    compiler.compile_scene = lambda *args: calls.append(args) or original(*args)
    try:
        (prepare_build if run else build_scene)(scene, out)
    finally:
        compiler.compile_scene = original
    return bool(calls)


@pytest.mark.parametrize("run", [False, True], ids=["build", "run"])
def test_whatever_a_build_is_made_from_changed_compiles_it(tmp_path, run):
    project = tmp_path / "project"
    (project / "components" / "sensors").mkdir(parents=True)
    (project / "morsec.toml").write_text("[project]\nname = 'p'\n", encoding="utf-8")
    scene = project / "scene.yaml"
    scene.write_text(SCENE, encoding="utf-8")
    out = tmp_path / "out"
    assert compiled(scene, out, run)
    assert not compiled(scene, out, run)

    scene.write_text(SCENE.replace("frequency: 60", "frequency: 50"), encoding="utf-8")  # the scene
    assert compiled(scene, out, run)
    assert not compiled(scene, out, run)

    (project / "components" / "sensors" / "notes.txt").write_text("a file of the catalogue", encoding="utf-8")
    assert compiled(scene, out, run)

    (out / "stray.txt").write_text("not part of the build", encoding="utf-8")  # the folder's files
    assert compiled(scene, out, run) and not (out / "stray.txt").exists()

    xml = out / "scene.xml"
    xml.write_text(xml.read_text(encoding="utf-8") + "<!-- edited -->\n", encoding="utf-8")
    assert compiled(scene, out, run)
    assert "edited" not in xml.read_text(encoding="utf-8")
    assert not compiled(scene, out, run)


def test_a_builder_script_is_always_run(tmp_path):
    script = tmp_path / "scene.py"
    script.write_text("from morse.builder import *\nrobot = ATRV()\nenv = Environment('empty')\n",
                      encoding="utf-8")
    assert buildcache.inputs_key(script) is None
    out = tmp_path / "out"
    assert compiled(script, out)
    assert compiled(script, out)


def test_without_a_writable_cache_every_build_compiles(scene, tmp_path, monkeypatch):
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("", encoding="utf-8")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker))
    out = tmp_path / "out"
    assert compiled(scene, out)
    assert compiled(scene, out)


@pytest.mark.parametrize("group", ["morsec.middlewares", "morsec.components", "console_scripts", "pytest11"])
def test_entry_points_are_those_importlib_finds(group):
    assert entry_points_of(group) == sorted(entry_points(group=group), key=lambda e: e.name)
