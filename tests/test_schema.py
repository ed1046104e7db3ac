"""schemas/scene.schema.json: `morsec schema`'s output, checked in, fresh, and agreeing with the loader."""

from __future__ import annotations

import json
import subprocess
import sys
import tomllib
from pathlib import Path

import jsonschema
import pytest
import yaml

from morsec.component.catalogue import load_catalogue
from morsec.scene.schema import json_schema_text

ROOT = Path(__file__).resolve().parent.parent
SCHEMA_FILE = ROOT / "schemas" / "scene.schema.json"
SCENES = sorted([*ROOT.glob("scenes/*.yaml"), *ROOT.glob("scenes/*.toml")])
REGENERATE = "morsec schema > schemas/scene.schema.json"


@pytest.fixture(autouse=True)
def _builtin_catalogue(monkeypatch):
    monkeypatch.delenv("MORSEC_COMPONENTS", raising=False)


@pytest.fixture(scope="module")
def schema() -> dict:
    return json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))


@pytest.fixture(scope="module")
def validator(schema) -> jsonschema.Draft202012Validator:
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


def read(path: Path):
    if path.suffix == ".toml":
        return tomllib.loads(path.read_text(encoding="utf-8"))
    return yaml.safe_load(path.read_text(encoding="utf-8"))


def test_checked_in_schema_is_fresh():
    fresh = json_schema_text(load_catalogue(ROOT))
    checked_in = SCHEMA_FILE.read_text(encoding="utf-8") if SCHEMA_FILE.is_file() else ""
    assert checked_in == fresh, (f"{SCHEMA_FILE.relative_to(ROOT)} is stale (the scene models or the component "
                                 f"catalogue changed): run `{REGENERATE}` from the repository root")


def test_morsec_schema_prints_it_deterministically():
    env_free = {"cwd": ROOT, "capture_output": True, "text": True, "timeout": 120}
    command = [sys.executable, "-c", "from morsec.cli import main; main()", "schema"]
    first = subprocess.run(command, **env_free)
    second = subprocess.run(command, **env_free)
    assert first.returncode == 0, first.stderr
    assert first.stdout == second.stdout == json_schema_text(load_catalogue(ROOT))


def test_there_are_example_scenes():
    assert any(p.suffix == ".yaml" for p in SCENES) and any(p.suffix == ".toml" for p in SCENES)


@pytest.mark.parametrize("path", SCENES, ids=[p.name for p in SCENES])
def test_example_scene_validates(validator, path):
    errors = sorted(validator.iter_errors(read(path)), key=lambda e: list(e.absolute_path))
    assert not errors, "\n".join(f"{list(e.absolute_path)}: {e.message[:300]}" for e in errors)


@pytest.mark.parametrize("name, scene", [
    ("unknown top-level key", {"robot": []}),
    ("unknown robot key", {"robots": [{"type": "atrv", "translat": [0, 0, 0]}]}),
    ("unknown robot type", {"robots": [{"type": "atrvv"}]}),
    ("missing robot type", {"robots": [{"name": "robot"}]}),
    ("unknown component type", {"robots": [{"type": "atrv", "components": [{"type": "poze"}]}]}),
    ("unknown component property", {"robots": [{"type": "atrv", "components": [
        {"type": "motion_vw", "properties": {"ControlTyp": "Position"}}]}]}),
    ("property of another component", {"robots": [{"type": "atrv", "components": [
        {"type": "pose", "properties": {"ControlType": "Position"}}]}]}),
    ("unknown level", {"robots": [{"type": "atrv", "components": [{"type": "odometry", "level": "diferential"}]}]}),
    ("translate of length 2", {"robots": [{"type": "atrv", "translate": [0, 0]}]}),
    ("string for a number", {"objects": [{"type": "box", "size": [1, "one", 1]}]}),
    ("zero frequency", {"environment": {"time": {"frequency": 0}}}),
    ("negative size", {"zones": [{"type": "Charging", "size": [1, -1, 1]}]}),
    ("unknown environment", {"environment": {"name": "sandbx"}}),
    ("unknown middleware", {"robots": [{"type": "atrv", "components": [{"type": "pose", "streams": ["sockett"]}]}]}),
])
def test_invalid_scene_is_rejected(validator, name, scene):
    assert list(validator.iter_errors(scene)), f"the schema accepts a scene with {name}"


def test_robots_and_components_are_unions_discriminated_on_type():
    cat = load_catalogue(ROOT)
    schema = json.loads(json_schema_text(cat))
    robots = schema["properties"]["robots"]["items"]
    assert robots["discriminator"]["propertyName"] == "type"
    for rid, cls in cat.by_kind["robots"].items():
        assert robots["discriminator"]["mapping"][rid] == robots["discriminator"]["mapping"][cls.builder_name]

    robot_def = schema["$defs"][robots["discriminator"]["mapping"][cat.ids("robots")[0]].rsplit("/", 1)[-1]]
    components = robot_def["properties"]["components"]["items"]
    if "$ref" in components:  # the union is one named definition, shared by robots and nested components
        components = schema["$defs"][components["$ref"].rsplit("/", 1)[-1]]
    assert components["discriminator"]["propertyName"] == "type"
    mapping = components["discriminator"]["mapping"]
    assert sorted({mapping[cid] for cid in cat.devices()}) == sorted(ref["$ref"] for ref in components["oneOf"])
    for cid, cls in sorted(cat.devices().items()):
        variant = schema["$defs"][mapping[cid].rsplit("/", 1)[-1]]
        assert sorted(variant["properties"]["type"]["enum"]) == sorted({cid, cls.builder_name})
        props_ref = variant["properties"]["properties"]["$ref"].rsplit("/", 1)[-1]
        props = schema["$defs"][props_ref]
        assert props.get("additionalProperties") is False
        assert sorted(props.get("properties", {})) == sorted(cls.Properties.model_fields), cid
        levels = [level.name for level in cls.levels]
        level_schema = json.dumps(variant["properties"]["level"])
        assert all(f'"{name}"' in level_schema for name in levels), cid


MANIFEST_SCHEMA = ROOT / "schemas" / "manifest.schema.json"


def test_checked_in_manifest_schema_is_fresh():
    from morsec.scene.manifest import manifest_schema_text
    checked_in = MANIFEST_SCHEMA.read_text(encoding="utf-8") if MANIFEST_SCHEMA.is_file() else ""
    assert checked_in == manifest_schema_text(), ("schemas/manifest.schema.json is stale: run "
                                                  "`morsec schema --manifest > schemas/manifest.schema.json`")


@pytest.mark.parametrize("scene", [ROOT / "scenes" / "tutorial.yaml", ROOT / "scenes" / "rover_laser.yaml"],
                         ids=lambda p: p.name)
def test_built_manifests_follow_the_manifest_schema(scene, tmp_path):
    from morsec.app.project import build_scene
    built = build_scene(scene, tmp_path / "build")
    manifest = json.loads((built / "manifest.json").read_text(encoding="utf-8"))
    schema = json.loads(MANIFEST_SCHEMA.read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator(schema).validate(manifest)
    broken = dict(manifest, streams=[{"component": "robot.pose"}])  # a stream without direction nor endpoint
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft202012Validator(schema).validate(broken)
