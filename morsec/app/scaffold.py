"""`morsec create` / `morsec add` / `morsec rm`: simulation projects and components from the jinja2
templates in templates/scaffold/ ("most of the boring parts are generated from templates")."""

from __future__ import annotations

import keyword
import re
import shutil
from dataclasses import dataclass
from pathlib import Path

import jinja2

from morsec.component.catalogue import PROJECT_FILE, camel_case, is_builtin, load_catalogue, project_root
from morsec.errors import MorsecError
from morsec.resources import data_dir

KINDS = {"sensor": "sensors", "actuator": "actuators", "robot": "robots"}
NAME = re.compile(r"^[a-z][a-z0-9_]*$")
SCHEMA_FILE = "scene.schema.json"  # the project's JSON Schema (its own components included), for editors


def _env() -> jinja2.Environment:
    return jinja2.Environment(loader=jinja2.FileSystemLoader(str(data_dir("templates") / "scaffold")),
                              undefined=jinja2.StrictUndefined, keep_trailing_newline=True)


def check_name(name: str, what: str) -> None:
    if not NAME.match(name) or keyword.iskeyword(name):
        raise MorsecError(f"invalid {what} name {name!r}: use lower-case letters, digits and underscores, "
                          "starting with a letter (a Python identifier such as thermal_cam)")


@dataclass
class Plan:
    """Files to write: {path: text}. Nothing is written until every check passed."""

    files: dict[Path, str]

    def write(self, force: bool) -> list[Path]:
        existing = [p for p in self.files if p.exists()]
        if existing and not force:
            raise MorsecError(f"{existing[0]} already exists; use --force to overwrite")
        for path, text in self.files.items():
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text, encoding="utf-8")
        return list(self.files)


def create_project(name: str, parent: Path, force: bool = False) -> Path:
    check_name(name, "project")
    root = Path(parent) / name
    if root.exists() and any(root.iterdir()) and not force:
        raise MorsecError(f"{root} exists and is not empty; use --force to write into it")
    env = _env()
    ctx = {"name": name, "schema_url": f"../{SCHEMA_FILE}"}
    files = {
        root / PROJECT_FILE: "project/morsec.toml.j2",
        root / "README.md": "project/README.md.j2",
        root / "scenes" / "default.yaml": "project/scenes/default.yaml.j2",
        root / "scenes" / "default.py": "project/scenes/default.py.j2",
        root / "scripts" / f"{name}_client.py": "project/scripts/client.py.j2",
        root / "tests" / "test_default.py": "project/tests/test_default.py.j2",
    }
    plan = Plan({path: env.get_template(template).render(**ctx) for path, template in files.items()})
    for kind in KINDS.values():
        plan.files[root / "components" / kind / ".keep"] = ""
    plan.write(force)
    write_schema(root)
    return root


def write_schema(root: Path) -> Path:
    """(Re)write the project's scene schema: after `add` and `rm` it lists the project's components."""
    from morsec.scene.schema import json_schema_text
    _forget_catalogue()
    path = root / SCHEMA_FILE
    path.write_text(json_schema_text(load_catalogue(root)), encoding="utf-8")
    return path


def _project(path: Path) -> Path:
    root = project_root(Path(path))
    if root is None:
        raise MorsecError(f"{path} is not in a morsec project (no {PROJECT_FILE} there or above); "
                          "create one with `morsec create NAME`")
    return root


def component_files(kind: str, name: str, root: Path) -> dict[Path, str]:
    """What `add` generates for a component: {path: template}."""
    folder = root / "components" / KINDS[kind] / name
    templates = {
        "sensor": {"component.py": "sensor/component.py.j2", "README.md": "sensor/README.md.j2",
                   "model.xml.j2": "sensor/model.xml.j2"},
        "actuator": {"component.py": "actuator/component.py.j2", "README.md": "actuator/README.md.j2"},
        "robot": {"component.py": "robot/component.py.j2", "README.md": "robot/README.md.j2",
                  "robot.urdf.xacro": "robot/robot.urdf.xacro.j2"},
    }[kind]
    files = {folder / f: t for f, t in templates.items()}
    files[root / "tests" / f"test_{name}.py"] = f"{kind}/test.py.j2"
    return files


def add_component(kind: str, name: str, project: Path, description: str, force: bool = False) -> list[Path]:
    if kind not in KINDS:
        raise MorsecError(f"unknown component kind {kind!r}: use sensor, actuator or robot")
    check_name(name, kind)
    root = _project(project)
    cat = load_catalogue(root)
    builtin = [c for c in cat.all() if is_builtin(c)]
    if (name in {c.id for c in builtin} or camel_case(name) in {c.builder_name for c in builtin}) and not force:
        raise MorsecError(f"{name!r} is a built-in component; choose another name or use --force to shadow it")
    env = _env()
    ctx = {"name": name, "cls": camel_case(name), "description": description.replace('"', "'").strip()}
    # the template's text is the example: jinja2 renders only the names and description into it
    files = component_files(kind, name, root)
    plan = Plan({path: env.get_template(template).render(**ctx) for path, template in files.items()})
    written = plan.write(force)
    write_schema(root)
    return written


def remove_component(kind: str, name: str, project: Path) -> list[Path]:
    if kind not in KINDS:
        raise MorsecError(f"unknown component kind {kind!r}: use sensor, actuator or robot")
    check_name(name, kind)
    root = _project(project)
    folder = root / "components" / KINDS[kind] / name
    if not folder.is_dir():
        raise MorsecError(f"no {kind} {name!r} in {root / 'components' / KINDS[kind]}")
    removed = []
    for path in component_files(kind, name, root):
        if path.is_file():
            path.unlink()
            removed.append(path)
    shutil.rmtree(folder)
    write_schema(root)
    return removed


def usage(kind: str, name: str) -> str:
    cls = camel_case(name)
    if kind == "robot":
        return (f"use it in a scene:\n  robots:\n    - {{name: rover, type: {name}}}\n"
                f"or in a builder script:\n  rover = {cls}()")
    return (f"use it in a scene:\n  components:\n    - {{name: {name}, type: {name}, streams: [socket]}}\n"
            f"or in a builder script:\n  {name} = {cls}()\n  robot.append({name})\n"
            f"see it: morsec components {name}; test it: python -m pytest tests/test_{name}.py")


def _forget_catalogue() -> None:
    from morsec.component import catalogue
    catalogue._load.cache_clear()
