"""The resolved IR -> the files of a build folder, written whole or not at all.

    scene.xml        MJCF that MuJoCo compiles without warnings
    robots/*.urdf    one per robot, xacro-expanded
    middleware.json  streams, services, ports
    manifest.json    the fully-resolved scene, component classes, versions and content hashes
"""

from __future__ import annotations

import glob
import hashlib
import json
import os
import re
import shutil
import tempfile
from pathlib import Path
from xml.sax.saxutils import escape as xml_escape

import mujoco
import numpy as np

from morsec import __version__
from morsec.compiler.assets import Assets
from morsec.compiler.middleware import assign_services, assign_streams, middleware_view
from morsec.compiler.mjcf import render_scene, static_robot
from morsec.compiler.urdf import expand_xacro, read_urdf
from morsec.component.catalogue import (
    Catalogue,
    declaring_folder,
    is_builtin,
    level_class,
    modifier_class,
    type_lineage,
)
from morsec.errors import SceneError, yaml_path
from morsec.kits.geometry import euler_to_quat, matrix_to_euler, quat_to_matrix
from morsec.kits.mjcf_names import belongs_to
from morsec.middleware.registry import middleware
from morsec.scene.manifest import (
    BUILTIN_ROOT,
    FORMAT_VERSION,
    MANIFEST,
    ComponentEntry,
    ComponentRef,
    Loop,
    Manifest,
    ModifierEntry,
    OverlayEntry,
    RobotEntry,
)
from morsec.scene.walk import walk_components

_NAME_PLACEHOLDER = "morsec__robot__name__placeholder"


def compile_scene(scene, cat: Catalogue) -> dict[str, str | bytes]:
    """Everything the build folder will hold, as {relative path: text}; nothing is written here."""
    components = component_entries(scene, cat)
    loop_frequency = loop_rate(scene, components)
    files: dict[str, str | bytes] = {}  # assets (meshes, textures) are bytes
    trees = {}
    robots = []
    assets = Assets()
    for r, robot in enumerate(scene.robots):
        cls = cat.get("robots", robot.type)
        xacro_file = declaring_folder(cls, "xacro") / cls.xacro
        try:
            if not xacro_file.is_file():
                raise SceneError(f"robot type {robot.type!r}: xacro file {cls.xacro!r} not found "
                                 f"(searched {xacro_file})")
            # xacro evaluates $(...) and ${...} in argument values: the name goes in after expansion, escaped
            urdf = expand_xacro(xacro_file, {"name": _NAME_PLACEHOLDER})
            urdf = urdf.replace(_NAME_PLACEHOLDER, xml_escape(robot.name, {'"': "&quot;"}))
            trees[robot.name] = read_urdf(urdf, f"{xacro_file}")
            for link in trees[robot.name].walk():
                for g in link.geoms:
                    if g.kind == "mesh":
                        g.mesh = assets.mesh(cls, g.mesh, g.size)
        except SceneError as err:
            raise _at_scene(err, scene, ("robots", r, "type")) from None
        path = f"robots/{robot.name}.urdf"
        files[path] = urdf
        robots.append(RobotEntry(name=robot.name, type=robot.type, component=component_ref(cls),
                                 builder_name=cls.builder_name or robot.type, urdf=path,
                                 free=not static_robot(robot, cls), friction=robot.friction,
                                 properties=robot.properties.model_dump(mode="json")))
    xml = render_scene(scene, cat, trees, loop_frequency, assets)
    check_mjcf(xml, scene, assets.files)
    files.update(assets.files)
    files["scene.xml"] = xml
    env = scene.environment
    placements = placements_on_robots(scene)
    streams = assign_streams([(c.fqn, cat.devices()[c.type].direction, specs, type_lineage(cat.devices()[c.type]),
                               c.properties, placements[c.fqn]) for c, specs in components])
    services = assign_services({c.fqn: c.services for c, _ in components}, env.services)
    managers = {name: spec.model_dump(mode="json") for name, spec in sorted(env.stream_managers.items())}
    files["middleware.json"] = dump(middleware_view(streams, services, managers))
    ir = scene.model_dump(mode="json")
    manifest = Manifest(
        format=FORMAT_VERSION, morsec=__version__, mujoco=mujoco.__version__,
        loop=Loop(frequency=loop_frequency, physics_substeps=env.time.physics_substeps,
                  timestep=1.0 / (loop_frequency * env.time.physics_substeps)),
        scene=ir, scene_sha256=sha256(dump(ir)), robots=robots, components=[c for c, _ in components],
        streams=streams, services=services, stream_managers=managers,
        files={name: sha256(text) for name, text in sorted(files.items())},
    )
    files[MANIFEST] = dump(manifest.model_dump(mode="json"))
    return files


def component_entries(scene, cat: Catalogue) -> list[tuple[ComponentEntry, list]]:
    """Each sensor and actuator of the scene, resolved, with the stream specs the scene gave it."""
    devices = cat.devices()
    env_properties = scene.environment.properties
    entries: list[tuple[ComponentEntry, list]] = []
    for robot, comp, fqn, parent, path in walk_components(scene):
        cls = devices[comp.type]
        impl = level_class(cls, comp.level)
        modifiers = []
        for spec in comp.modifiers:
            mod_cls = modifier_class(spec.name, cls)
            assert mod_cls is not None, f"{fqn}: modifier {spec.name!r} does not apply (resolve() checks it)"
            params = mod_cls.resolve_params(dict(spec.model_extra or {}), env_properties)
            modifiers.append(ModifierEntry(name=spec.name, cls=f"{mod_cls.__module__}:{mod_cls.__qualname__}",
                                           params=params.model_dump(mode="json")))
        overlays = [OverlayEntry(middleware=o.middleware, overlay=o.overlay,
                                 cls=middleware(o.middleware).overlay_class(o.overlay, type_lineage(cls)),
                                 params=dict(o.model_extra or {})) for o in comp.overlays]
        entries.append((ComponentEntry(
            fqn=fqn, robot=robot.name, parent=parent, type=comp.type, kind=cls.kind, component=component_ref(cls),
            level_class=impl.__name__ if impl.__module__ == cls.__module__ else f"{impl.__module__}.{impl.__name__}",
            level=comp.level, frequency=comp.frequency,
            properties=comp.properties.model_dump(mode="json"),
            data_fields=[f.name for f in impl.fields_at(comp.level)],
            services=comp.services, service_names=sorted(impl.services()), modifiers=modifiers, overlays=overlays,
            tags=comp.tags,
            path=list(path),
        ), comp.streams))
    return entries


def placements_on_robots(scene) -> dict[str, tuple[list[float], list[float]]]:
    """Each component's position and XYZ Euler rotation on its robot, as the scene placed it (a nested
    component's `translate` and `rotate` composed with its parents')."""
    frames: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    out = {}
    for placed in walk_components(scene):
        comp = placed.component
        local = quat_to_matrix(euler_to_quat(*comp.rotate))
        position, rotation = np.array(comp.translate, float), local
        if placed.parent in frames:
            parent_position, parent_rotation = frames[placed.parent]
            position, rotation = parent_position + parent_rotation @ position, parent_rotation @ local
        frames[placed.fqn] = (position, rotation)
        out[placed.fqn] = ([float(v) for v in position], [float(v) for v in matrix_to_euler(rotation)])
    return out


def component_ref(cls) -> ComponentRef:
    if getattr(cls, "classpath", None):
        return ComponentRef(root=str(cls.import_root), kind=f"{cls.kind}s", id=cls.id, name=cls.__name__,
                            module=cls.__module__)
    root = Path(cls.folder).parent.parent
    return ComponentRef(root=BUILTIN_ROOT if is_builtin(cls) else str(root.resolve()), kind=f"{cls.kind}s",
                        id=cls.id, name=cls.__name__)


def loop_rate(scene, components: list[tuple[ComponentEntry, list]]) -> float:
    """The main loop's frequency; with auto-tune (MORSE's default) raised to the fastest component."""
    time = scene.environment.time
    fastest = max((c.frequency for c, _ in components), default=0.0)
    return max(time.frequency, fastest) if time.auto_tune else time.frequency


_MJ_ELEMENT = re.compile(r"Element name '([^']*)', id \d+, line (\d+)")


def check_mjcf(xml: str, scene, assets: dict[str, bytes] | None = None) -> None:
    """Compile with MuJoCo; a rejection is re-anchored to the scene entry that produced the element."""
    try:
        mujoco.MjModel.from_xml_string(xml, assets=assets or {})
    except ValueError as err:
        raise _anchor(str(err), xml, scene) from None


def _anchor(message: str, xml: str, scene) -> SceneError:
    first = message.strip().splitlines()[0].removeprefix("Error: ")
    m = _MJ_ELEMENT.search(message)
    owner = None
    if m:
        owner = m.group(1) or _enclosing_body(xml, int(m.group(2)))
    path = _scene_path(scene, owner) if owner else None
    smap = scene._source
    pos = smap.find(path) if (smap and path) else None
    line, col = pos if pos else (None, None)
    what = f" (from {owner!r})" if owner else ""
    where = f"{yaml_path(path)}: " if (smap and path) else ""
    return SceneError(f"{where}MuJoCo rejected the compiled scene{what}: {first}", smap.file if smap else None,
                      line, col)


def _at_scene(err: SceneError, scene, path: tuple) -> SceneError:
    """An error found while compiling one scene entry, placed at that entry of the scene file."""
    smap = scene._source
    if err.file is not None or smap is None:
        return err
    pos = smap.find(path)
    line, col = pos if pos else (None, None)
    return SceneError(f"{yaml_path(path)}: {err.message}", smap.file, line, col)


def _enclosing_body(xml: str, line: int) -> str | None:
    for text in reversed(xml.splitlines()[:line]):
        m = re.search(r'<body name="([^"]*)"', text)
        if m:
            return m.group(1).replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", '"').replace("&amp;", "&")
    return None


def _scene_path(scene, body: str) -> tuple | None:
    for r, robot in enumerate(scene.robots):
        if belongs_to(body, robot.name):
            return ("robots", r)
    for placed in walk_components(scene):
        if body == placed.fqn:
            return placed.path
    for i, obj in enumerate(scene.objects):
        if body == obj.name:
            return ("objects", i)
    return None


def write_build(files: dict[str, str | bytes], out_dir: Path) -> None:
    """Write all files into a fresh temporary folder, then put it in place of `out_dir`; a previous build
    there is replaced only once the new one is complete, and a folder that is not a build is never touched."""
    out_dir = out_dir.resolve()
    if out_dir.exists() and not out_dir.is_dir():
        raise SceneError(f"{out_dir}: exists and is not a folder; choose another build folder with -o")
    if out_dir.exists() and not (out_dir / MANIFEST).is_file() and any(out_dir.iterdir()):
        raise SceneError(f"{out_dir}: refusing to replace a folder that is not a morsec build (no {MANIFEST}); "
                         "choose another build folder with -o")
    try:
        out_dir.parent.mkdir(parents=True, exist_ok=True)
        remove_leftovers(out_dir)
        tmp = _scratch(out_dir, "partial")
    except OSError as err:
        raise SceneError(f"{out_dir}: cannot create the build folder: {err.strerror or err}") from None
    old = None
    try:
        for name, content in files.items():
            target = tmp / name
            target.parent.mkdir(parents=True, exist_ok=True)
            if isinstance(content, bytes):
                target.write_bytes(content)
            else:
                target.write_text(content, encoding="utf-8")
        if out_dir.exists():
            old = _scratch(out_dir, "old")
            out_dir.rename(old / "build")
        tmp.rename(out_dir)
    except BaseException as err:
        shutil.rmtree(tmp, ignore_errors=True)
        if old is not None and (old / "build").exists() and not out_dir.exists():
            (old / "build").rename(out_dir)  # put the previous build back
        if old is not None:
            shutil.rmtree(old, ignore_errors=True)
        if isinstance(err, OSError):
            raise SceneError(f"{out_dir}: cannot write the build: {err.strerror or err}") from None
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def _scratch(out_dir: Path, kind: str) -> Path:
    """A hidden folder beside out_dir, named after this process: .NAME.KIND-PID-XXXXXXXX."""
    return Path(tempfile.mkdtemp(prefix=f".{out_dir.name}.{kind}-{os.getpid()}-", dir=out_dir.parent))


def remove_leftovers(out_dir: Path) -> None:
    """Remove the hidden folders of builds of out_dir that were killed while writing (their process is
    gone); those of a build still running are left alone."""
    pattern = re.compile(rf"\.{re.escape(out_dir.name)}\.(partial|old)-(\d+)-[^/]+")
    for path in out_dir.parent.glob(f".{glob.escape(out_dir.name)}.*-*-*"):
        match = pattern.fullmatch(path.name)
        if match and path.is_dir() and not path.is_symlink() and not _alive(int(match.group(2))):
            shutil.rmtree(path, ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):  # another user's process; not a pid at all: left alone
        return True
    return True


def dump(data) -> str:
    return json.dumps(data, indent=2, sort_keys=True) + "\n"


def sha256(content: str | bytes) -> str:
    return hashlib.sha256(content if isinstance(content, bytes) else content.encode("utf-8")).hexdigest()
