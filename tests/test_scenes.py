"""Every example scene under scenes/ builds, loads in MuJoCo and runs; builds are reproducible; the TOML
tutorial is the exact twin of the YAML one."""

from __future__ import annotations

import json
from pathlib import Path

import mujoco
import numpy as np
import pytest

from morsec.app.project import build_scene

SCENES_DIR = Path(__file__).resolve().parent.parent / "scenes"
SCENE_SUFFIXES = (".yaml", ".yml", ".toml")
SCENES = sorted(p for p in SCENES_DIR.iterdir() if p.suffix in SCENE_SUFFIXES)
YAML_SCHEMA_LINE = "# yaml-language-server: $schema=../schemas/scene.schema.json"


def folder_bytes(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_there_are_example_scenes():
    names = {p.name for p in SCENES}
    assert {"tutorial.yaml", "tutorial.toml"} <= names
    assert len(SCENES) >= 3


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.name)
def test_scene_builds_loads_and_runs(scene, tmp_path):
    out = build_scene(scene, tmp_path / "build")
    files = folder_bytes(out)
    assert {"scene.xml", "manifest.json", "middleware.json"} <= set(files)
    manifest = json.loads(files["manifest.json"])
    for robot in manifest["robots"]:
        assert robot["urdf"] in files
    assert set(manifest["files"]) == set(files) - {"manifest.json"}

    model = mujoco.MjModel.from_xml_path(str(out / "scene.xml"))
    data = mujoco.MjData(model)
    for robot in manifest["robots"]:
        assert model.body(robot["name"]).id > 0
    mujoco.mj_step(model, data, nstep=round(1.0 / model.opt.timestep))
    assert data.time == pytest.approx(1.0)
    assert np.isfinite(data.qpos).all() and np.isfinite(data.qvel).all()
    warnings = {mujoco.mjtWarning(i).name: w.number for i, w in enumerate(data.warning) if w.number}
    assert not warnings, f"MuJoCo warnings: {warnings}"


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.name)
def test_build_is_reproducible(scene, tmp_path):
    first = folder_bytes(build_scene(scene, tmp_path / "first"))
    second = folder_bytes(build_scene(scene, tmp_path / "second"))
    assert first == second
    again = folder_bytes(build_scene(scene, tmp_path / "first"))  # rebuilding in place
    assert again == first


@pytest.mark.parametrize("scene", [p for p in SCENES if p.suffix in (".yaml", ".yml")], ids=lambda p: p.name)
def test_yaml_scene_names_its_schema(scene):
    assert scene.read_text(encoding="utf-8").splitlines()[0] == YAML_SCHEMA_LINE


def test_tutorial_toml_is_the_yaml_twin(tmp_path):
    from_yaml = build_scene(SCENES_DIR / "tutorial.yaml", tmp_path / "yaml")
    from_toml = build_scene(SCENES_DIR / "tutorial.toml", tmp_path / "toml")
    assert (from_toml / "manifest.json").read_bytes() == (from_yaml / "manifest.json").read_bytes()
    assert folder_bytes(from_toml) == folder_bytes(from_yaml)
