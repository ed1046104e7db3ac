"""Render scene.xml from the resolved IR through the jinja2 templates in templates/mjcf/ and each
component folder's own fragment (model.xml.j2, environment.xml.j2)."""

from __future__ import annotations

import copy
import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

import jinja2
import numpy as np
from markupsafe import Markup, escape

from morsec import __version__
from morsec.compiler.assets import Assets, asset_dir
from morsec.compiler.urdf import Link, expand_xacro, read_urdf
from morsec.component.catalogue import Catalogue, declaring_folder
from morsec.component.contract import Component, Environment, Prop
from morsec.errors import SceneError
from morsec.kits import mjcf_names
from morsec.kits.geometry import euler_to_quat, fmt, fmt_vec, matrix_to_quat, quat_to_matrix
from morsec.kits.mjcf_names import part
from morsec.resources import data_dir
from morsec.scene.naming import join
from morsec.scene.walk import walk_children, walk_components

SENSOR_WIDTH_MM = 32.0
STAT_EXTENT = 10.0  # MuJoCo's model size statistic, fixed (it scales clip planes, haze, default views)
# base velocity servo gains per kg of robot: stiff enough to override wheel/ground friction when
# turning (MORSE's motion actuators are kinematic); implicitfast integrates them stably
SERVO_GAIN_PER_KG = 200.0
# a lock (Blender's lock_location_z ...) is a velocity damper on the body's free joint, in the world frame:
# under gravity alone a locked body drifts at g / LOCK_GAIN_PER_KG (0.01 mm/s); implicitfast keeps it stable
LOCK_GAIN_PER_KG = 1.0e6
LOCK_GEARS = {"location_x": "1 0 0 0 0 0", "location_y": "0 1 0 0 0 0", "location_z": "0 0 1 0 0 0",
              "rotation_x": "0 0 0 1 0 0", "rotation_y": "0 0 0 0 1 0", "rotation_z": "0 0 0 0 0 1"}


def template_env(cat: Catalogue) -> jinja2.Environment:
    loader = jinja2.FileSystemLoader([str(data_dir("templates")), *[str(r) for r in cat.roots]])
    env = jinja2.Environment(loader=loader, autoescape=True, undefined=jinja2.StrictUndefined,
                             trim_blocks=True, lstrip_blocks=True, keep_trailing_newline=False,
                             finalize=_xml_text)
    env.filters["f"] = fmt
    env.filters["v"] = fmt_vec
    env.globals["mjcf"] = mjcf_names  # templates spell MJCF names through morsec.kits.mjcf_names
    return env


def _xml_text(value: Any) -> Any:
    """Every text a template inserts, escaped, with '--' written '-&#45;': names go into XML comments too,
    where '--' may not appear; in attributes and text, XML parsers read it back as '--'."""
    if isinstance(value, str) and not isinstance(value, Markup):
        return Markup(str(escape(value)).replace("--", "-&#45;"))
    return value


def render(env: jinja2.Environment, template: str, **context: Any) -> Markup:
    """Render a template; the result is markup, inserted unescaped into the template that includes it."""
    try:
        return Markup(env.get_template(template).render(**context).strip("\n"))
    except jinja2.TemplateNotFound as err:
        searched = ", ".join(getattr(env.loader, "searchpath", ()))
        raise SceneError(f"template not found: {err.name} (searched {searched})") from None
    except jinja2.TemplateError as err:
        where = f"{getattr(err, 'filename', None) or template}:{getattr(err, 'lineno', '') or ''}"
        raise SceneError(f"{where}: template error: {err}") from None


def component_template(cat: Catalogue, cls, filename: str) -> str | None:
    """Template path relative to the catalogue root holding the component, or None if the folder has none."""
    folder: Path = cls.folder
    if not (folder / filename).is_file():
        return None
    for root in cat.roots:
        try:
            return (folder / filename).relative_to(root).as_posix()
        except ValueError:
            continue
    return None


def _own_template(cat: Catalogue, cls: type[Environment] | type[Prop], filename: str) -> str:
    """The template an environment or a prop is made of (its class's `template`), which its folder must have."""
    template = component_template(cat, cls, filename)
    if template is None:
        raise SceneError(f"{cls.kind} {cls.id!r}: no {filename} in its folder {cls.folder}")
    return template


@dataclass
class RobotBody:
    """What the robot template needs, computed from the IR and the robot's URDF link tree."""

    name: str
    type: str
    root: Link
    components: list[dict]
    free: bool
    gravcomp: bool
    friction: float | None
    collides: bool
    frictionless: bool = False  # its contacts carry no friction (see _driven_by_velocity)
    sites: list[dict] = field(default_factory=list)  # more sites on the base body: name, pos


def render_scene(scene, cat: Catalogue, robot_trees: dict[str, Link], loop_frequency: float,
                 assets: Assets) -> str:
    env = template_env(cat)
    environment = cat.get("environments", scene.environment.name)
    env_context = {"scene": scene, "environment": scene.environment, "asset_dir": asset_dir(environment),
                   "id": environment.id}
    env_xml = render(env, _own_template(cat, environment, environment.template), **env_context)
    terrain = environment.terrain.mjcf() if environment.terrain is not None else None
    if environment.layout or terrain:
        env_xml = Markup("\n").join([env_xml, render(env, "mjcf/layout.xml.j2", parts=environment.layout,
                                                     terrain=terrain)])
    asset_xml = [_class_assets(environment, cat, env, assets, env_context)]
    if terrain:
        asset_xml.append(render(env, "mjcf/layout_assets.xml.j2", terrain=terrain))
    for cls in _used_classes(scene, cat):
        context: dict[str, Any] = {"asset_dir": asset_dir(cls), "id": cls.id}
        if cls.kind == "prop":  # a prop scaled by its objects' sizes declares its meshes at each (mesh scale)
            context["sizes"] = _prop_sizes(scene, cat, cls)
        asset_xml.append(_class_assets(cls, cat, env, assets, context))

    robots = [render(env, "mjcf/robot.xml.j2", robot=_robot_body(r, cat, env, robot_trees[r.name]))
              for r in scene.robots]
    objects = [_object(o, cat, env) for o in scene.objects]
    servos = [_servo(r, cat, robot_trees[r.name]) for r in scene.robots if _needs_servo(r, cat)]
    locks = _locks(scene, cat, robot_trees)
    dampers = [d for r in scene.robots if (d := _dampers(r, cat, robot_trees[r.name]))]
    sections = _component_sections(scene, cat, env, robot_trees)
    zones = [{"name": z.name, "pos": z.translate, "half": [s / 2 for s in z.size]} for z in scene.zones]

    cam = scene.environment.camera
    viewport_w, viewport_h = 800, 600
    fov_h = 2 * math.atan(SENSOR_WIDTH_MM / 2 / cam.focal)
    fovy = math.degrees(2 * math.atan(math.tan(fov_h / 2) * viewport_h / viewport_w))
    substeps = scene.environment.time.physics_substeps
    return pretty_xml(render(
        env, "mjcf/scene.xml.j2",
        model_name=_model_name(scene), morsec_version=__version__,
        timestep=1.0 / (loop_frequency * substeps), gravity=scene.environment.gravity,
        offwidth=1920, offheight=1080,
        camera={"pos": cam.location, "quat": euler_to_quat(*cam.rotation), "fovy": fovy, "clip": cam.clip},
        extent=STAT_EXTENT,
        environment=env_xml, environment_assets=Markup("\n").join(a for a in asset_xml if a),
        meshes=[{"name": n, "file": f, "scale": sc} for n, (f, sc) in sorted(assets.meshes.items())],
        robots=robots, objects=objects, zones=zones, servos=servos, locks=locks, dampers=dampers,
        actuators=sections["actuator.xml.j2"], sensors=sections["sensor.xml.j2"],
        equalities=sections["equality.xml.j2"],
    ), mounts=_mounts(scene, cat))


def pretty_xml(text: str, mounts: dict[str, tuple[str, str | None]] | None = None) -> str:
    """Parse (which also proves the templates produced well-formed XML), move mounted components' bodies
    (see `_mounts`) and re-indent."""
    try:
        root = ET.fromstring(text, parser=ET.XMLParser(target=ET.TreeBuilder(insert_comments=True)))
    except ET.ParseError as err:
        raise SceneError(f"internal error: generated MJCF is not well-formed XML: {err}") from None
    if mounts:
        _move_bodies(root, mounts)
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode") + "\n"


def _model_name(scene) -> str:
    return "morsec " + scene.environment.name


def _class_assets(cls, cat: Catalogue, env, assets: Assets, context: dict) -> str:
    """A component folder's assets.xml.j2 (meshes, textures, materials), its files copied into the build."""
    template = component_template(cat, cls, "assets.xml.j2")
    if not template:
        return ""
    assets.copy_folder(cls)
    return render(env, template, **context)


def _used_classes(scene, cat: Catalogue) -> list[type[Component]]:
    """Every robot, device and prop class the scene uses, once each, in a stable order."""
    found: dict[str, type[Component]] = {}
    for robot in scene.robots:
        cls: type[Component] = cat.get("robots", robot.type)
        found.setdefault(f"robot/{cls.id}", cls)
    for placed in walk_components(scene):
        cls = cat.devices()[placed.component.type]
        found.setdefault(f"{cls.kind}/{cls.id}", cls)
    for obj in scene.objects:
        cls = cat.get("props", obj.type)
        found.setdefault(f"prop/{cls.id}", cls)
    return [found[k] for k in sorted(found)]


def _prop_sizes(scene, cat: Catalogue, cls: type[Component]) -> list[list[float]]:
    """The distinct sizes the scene's objects of prop `cls` have, in a stable order."""
    sizes = {tuple(o.size) for o in scene.objects if cat.get("props", o.type) is cls}
    return [list(size) for size in sorted(sizes)]


def static_robot(robot, cls) -> bool:
    """Whether a robot has no free joint (its scene's physics_type, or its class, says static): one fact for the
    free joint, and for the servos and dampers that act on it."""
    return robot.physics_type == "static" or cls.static


def _robot_body(robot, cat: Catalogue, env, tree: Link) -> RobotBody:
    cls = cat.get("robots", robot.type)
    static = static_robot(robot, cls)
    collides = robot.collision and robot.ghost is None and robot.physics_type != "no_collision" and cls.collision
    _prepare_links(tree, robot)
    # per-joint MuJoCo armature (drive-train inertia reflected through a gearbox) declared by the robot
    # class: {URDF joint name: kg m^2}; URDF has no field for it
    armature = getattr(cls, "joint_armature", {}) or {}
    for link in tree.walk():
        if link.joint and link.joint["name"] in armature:
            link.joint["armature"] = float(armature[link.joint["name"]])
    x, y, z = (float(v) for v in robot.translate)
    tree.pos = np.array([x, y, cls.origin_z(z, robot.properties)])
    tree.quat = euler_to_quat(*(r + o for r, o in zip(robot.rotate, cls.origin_rotation)))
    floats = bool(robot.properties.NoGravity)  # its arms float with it
    components = [_component(c, robot.name, cat, env, floats) for c in robot.components]
    sites = []
    if not static and (_damped(robot, cat) or robot.locks):
        sites.append({"name": mjcf_names.centre_of_mass(robot.name), "pos": mass_properties(tree)[1]})
    return RobotBody(name=robot.name, type=robot.type, root=tree, components=components, free=not static,
                     gravcomp=bool(robot.properties.NoGravity), friction=robot.friction, collides=collides,
                     frictionless=not static and _driven_by_velocity(robot, cat), sites=sites)


SECTION_TEMPLATES = ("actuator.xml.j2", "sensor.xml.j2", "equality.xml.j2")


def _component_sections(scene, cat: Catalogue, env, robot_trees: dict[str, Link]) -> dict[str, list]:
    """A component folder may add MJCF <actuator> entries (actuator.xml.j2: e.g. wheel motors), MuJoCo
    <sensor> entries (sensor.xml.j2) and <equality> constraints (equality.xml.j2: e.g. a gripper's welds).
    Context: name (fqn), robot, robot_type, robot_class (the robot's catalogue class: its class attributes,
    e.g. wheel joints and radius), robot_properties, joints (the robot's MJCF joint names by URDF name),
    links (MJCF body names by URDF link name), own_joints (the joints of the component's own xacro, root to
    tip: dicts with name, mjname, type hinge|slide, range or None), objects (the scene's passive objects:
    name, dynamic, properties ...), properties, component."""
    devices = cat.devices()
    out: dict[str, list] = {t: [] for t in SECTION_TEMPLATES}

    for robot, comp, fqn, _, _ in walk_components(scene):
        cls = devices[comp.type]
        tree = robot_trees[robot.name]
        joints = {link.joint["name"]: part(robot.name, link.joint["name"]) for link in tree.walk() if link.joint}
        links = {link.name: (robot.name if link is tree else part(robot.name, link.name)) for link in tree.walk()}
        own = device_links(cls, fqn)
        own_joints = [{"name": link.joint["name"], "mjname": link.joint["mjname"], "type": link.joint["type"],
                       "range": link.joint["range"]} for link in (own.walk() if own else ()) if link.joint]
        for template in SECTION_TEMPLATES:
            path = component_template(cat, cls, template)
            if path:
                out[template].append(render(env, path, name=fqn, robot=robot.name, robot_type=robot.type,
                                            robot_class=cat.get("robots", robot.type),
                                            robot_properties=robot.properties,
                                            joints=joints, links=links, own_joints=own_joints,
                                            objects=scene.objects, properties=comp.properties,
                                            component=comp))
    return out


def _driven_by_velocity(robot, cat: Catalogue) -> bool:
    """A ground robot whose body velocity an actuator sets (its base servos hold it; MORSE set it at each tick):
    its contacts carry no friction. MORSE's ground friction on it is the servos' targets' (kits.ground_friction),
    and MuJoCo's sliding friction would lift it: a contact sliding at v separates at up to mu v in MuJoCo's
    convex contact model, so that an ATRV driven sideways at 1 m/s hopped (+-0.1 m/s up and down) and rocked
    (+-0.3 rad/s), against the ground's 0.5 or 0.25 as well as 1. The robot's geoms take precedence (priority)
    over the other geom of each contact, the ground's, an object's."""
    return bool(getattr(robot.properties, "GroundRobot", False)) and _needs_servo(robot, cat)


def _needs_servo(robot, cat: Catalogue) -> bool:
    devices = cat.devices()
    return any(getattr(devices[placed.component.type], "base_servo", False)
               for placed in walk_children(robot, robot.components, robot.name, ()))


def _locks(scene, cat: Catalogue, robot_trees: dict[str, Link]) -> list[dict]:
    """A damper per locked axis of a moving robot or object: a velocity actuator from the body's site,
    measured in the world frame (refsite), so that nothing moves it along (or turns it about) that axis.
    A robot's acts at its centre of mass, as Bullet's locks (they hold the body's centre of mass, which is
    a Blender robot's origin): held at its origin, below it, a robot held up by a lock would balance on a
    point and topple."""
    out = []
    for robot in scene.robots:
        static = static_robot(robot, cat.get("robots", robot.type))
        if robot.locks and not static:
            mass = robot.mass or sum(link.mass for link in robot_trees[robot.name].walk()) or 1.0
            out += _lock_entries(robot.name, robot.locks, mass, site=mjcf_names.centre_of_mass(robot.name))
    for obj in scene.objects:
        if obj.locks and obj.dynamic:
            out += _lock_entries(obj.name, obj.locks, obj.mass)
    return out


def _lock_entries(owner: str, locks: list[str], mass: float, site: str | None = None) -> list[dict]:
    return [{"name": mjcf_names.lock(owner, axis), "site": site or owner, "gear": LOCK_GEARS[axis],
             "kv": LOCK_GAIN_PER_KG * mass} for axis in LOCK_GEARS if axis in locks]


# A site transmission costs MuJoCo, at every physics step, a dense Jacobian over all the model's dofs per actuator:
# quadratic in the number of robots (128 ATRVs: three quarters of the step). A free joint's rotational dofs are
# its body's angular velocity in the body's own frame, so a rate about the base's axes (the yaw servo; the angular
# dampers, whose torque acts alike wherever applied) is a joint transmission on those dofs instead: the same
# forces, to the rounding, at a cost that does not grow with the model. Linear velocities along the base's axes
# are not dofs (the free joint's are the origin's, in the world frame): those stay site transmissions.

def _servo(robot, cat: Catalogue, tree: Link) -> dict:
    mass = robot.mass or sum(link.mass for link in tree.walk()) or 1.0
    gain = SERVO_GAIN_PER_KG * mass
    static = static_robot(robot, cat.get("robots", robot.type))
    return {"robot": robot.name, "kv_linear": gain, "kv_angular": gain, "joint": None if static else robot.name}


# ---- damping: Blender gave each rigid body of the game Bullet's velocity damping, v *= (1 - d) ** dt at each
# step (the object's Physics panel: Damping, Rotation Damping; by default 0.04 and 0.1), so that a free robot
# pushed then let go slows down. Here a damper per axis on the robot's base, at its centre of mass: a force
# -m c v along x, y, z and a torque -I c w about them, c = -ln(1 - d) (the same loss per second), m and I the
# robot's links' (at rest, in the base frame). An affine-bias actuator, which MuJoCo's implicitfast integrator
# takes implicitly; its control is unused.

def _damped(robot, cat: Catalogue) -> bool:
    cls = cat.get("robots", robot.type)
    static = static_robot(robot, cls)
    collides = robot.collision and robot.ghost is None and robot.physics_type != "no_collision" and cls.collision
    return not static and collides and any(d > 0 for d in cls.damping)


def _dampers(robot, cat: Catalogue, tree: Link) -> dict | None:
    if not _damped(robot, cat):
        return None
    linear, angular = (-math.log(1.0 - min(max(d, 0.0), 0.999)) for d in cat.get("robots", robot.type).damping)
    mass, _, inertia = mass_properties(tree)
    kv = [linear * mass] * 3 + [angular * float(i) for i in np.diag(inertia)]
    return {"robot": robot.name, "site": mjcf_names.centre_of_mass(robot.name),
            "axes": [{"name": mjcf_names.damper(robot.name, axis), "gear": gear, "kv": k,
                      "joint": robot.name if axis.startswith("r") else None}  # rx, ry, rz: on its free joint
                     for axis, gear, k in zip(mjcf_names.DAMPER_AXES, _GEARS, kv) if k > 0]}


_GEARS = ("1 0 0 0 0 0", "0 1 0 0 0 0", "0 0 1 0 0 0", "0 0 0 1 0 0", "0 0 0 0 1 0", "0 0 0 0 0 1")


def mass_properties(tree: Link) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, centre of mass, 3x3 inertia about it) of a robot's links at rest (joints at zero), in the
    frame of its base link."""
    bodies = []  # (mass, centre in the base frame, inertia about it in the base frame)

    def visit(link: Link, rot: np.ndarray, pos: np.ndarray) -> None:
        if link.mass > 0:
            ixx, iyy, izz, ixy, ixz, iyz = link.inertia
            local = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
            bodies.append((link.mass, pos + rot @ link.inertial_pos, rot @ local @ rot.T))
        for child in link.children:
            visit(child, rot @ quat_to_matrix(child.quat), pos + rot @ child.pos)

    visit(tree, np.eye(3), np.zeros(3))
    mass = sum(b[0] for b in bodies)
    if mass <= 0:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    com = sum(m * c for m, c, _ in bodies) / mass
    inertia = np.zeros((3, 3))
    for m, c, i in bodies:
        r = c - com
        inertia += i + m * (float(r @ r) * np.eye(3) - np.outer(r, r))
    return mass, com, inertia


def _prepare_links(tree: Link, robot) -> None:
    total = sum(link.mass for link in tree.walk())
    scale = (robot.mass / total) if (robot.mass and total > 0) else 1.0
    color = list(robot.color) + [1.0] if robot.color and len(robot.color) == 3 else robot.color
    for link in tree.walk():
        link.body = robot.name if link is tree else part(robot.name, link.name)
        link.mass *= scale
        link.inertia = link.inertia * scale
        if link.joint:
            link.joint["mjname"] = part(robot.name, link.joint["name"])
        has_visual = any(not g.collision for g in link.geoms)
        for g in link.geoms:
            g.visible = g.collision and not has_visual
            if color and (not g.collision or g.visible):
                g.rgba = color
            if robot.ghost is not None and (not g.collision or g.visible):
                g.rgba = list((g.rgba or [0.5, 0.5, 0.5, 1.0])[:3]) + [robot.ghost]


def _component(comp, parent_fqn: str, cat: Catalogue, env, gravcomp: bool = False) -> dict:
    cls = cat.devices()[comp.type]
    fqn = join(parent_fqn, comp.name)
    template = component_template(cat, cls, "model.xml.j2")
    fragment = ""
    if template:
        fragment = render(env, template, name=fqn, properties=comp.properties, component=comp,
                          color=comp.color)
    arm = device_links(cls, fqn)
    return {
        "fqn": fqn, "pos": comp.translate, "quat": euler_to_quat(*comp.rotate), "fragment": fragment,
        # an arm's links (device_links), rendered with the robots' link macro: no free joint, no contacts
        "arm": RobotBody(name=fqn, type=cls.id, root=arm, components=[], free=False, gravcomp=gravcomp,
                         friction=None, collides=False) if arm is not None else None,
        "children": [_component(child, fqn, cat, env, gravcomp) for child in comp.components],
    }


# ---- components with their own kinematics (arms) and components mounted on one of their bodies

def device_links(cls, fqn: str) -> Link | None:
    """The link tree of a sensor or actuator whose class names a xacro file of its folder (`xacro =
    "arm.urdf.xacro"`: an arm), rendered inside the component's body: URDF link L becomes body `<fqn>/L`,
    joint J `<fqn>/J` (the robots' rule with the component's name). Its geoms never collide; per-joint
    MuJoCo armature from the class's `joint_armature` ({joint: kg m^2}; "*": the joints it does not name).
    None for a component without one."""
    name = getattr(cls, "xacro", None)
    if not name:
        return None
    path = declaring_folder(cls, "xacro") / name  # a subclass that keeps its parent's arm finds it there
    tree = copy.deepcopy(_device_tree(path, path.stat().st_mtime_ns if path.is_file() else 0))
    armature = getattr(cls, "joint_armature", {}) or {}
    for link in tree.walk():
        link.body = part(fqn, link.name)
        has_visual = any(not g.collision for g in link.geoms)
        for g in link.geoms:
            if g.kind == "mesh":
                raise SceneError(f"{path}: link {link.name!r}: meshes are not supported in a component's xacro "
                                 "(use boxes, cylinders and spheres)")
            g.visible = g.collision and not has_visual
        if link.joint:
            link.joint["mjname"] = part(fqn, link.joint["name"])
            value = armature.get(link.joint["name"], armature.get("*"))  # "*": every other joint's
            if value is not None:
                link.joint["armature"] = float(value)
    return tree


@lru_cache(maxsize=32)
def _device_tree(path: Path, mtime_ns: int) -> Link:
    return read_urdf(expand_xacro(path, {}), str(path))


def _mounts(scene, cat: Catalogue) -> dict[str, tuple[str, str | None]]:
    """{child component body: (body to nest it in, None or the component whose frame its pose is in)} for the
    children of components whose class sets `mount_body` (a body of its own model, named relative to the
    component: "tilt" -> `<fqn>/tilt`): a camera on a pan-tilt unit goes in the tilt body, a gripper on an arm
    in its last link. A class that also sets `mount_in_own_frame` (an armature, as MORSE's) reads its
    children's translate / rotate in its own frame, its joints at zero: they keep that place, carried by the
    mount body. And the components a robot class mounts on another one's body (`component_mounts`)."""
    devices = cat.devices()
    out: dict[str, tuple[str, str | None]] = {}
    for _, comp, fqn, _, _ in walk_components(scene):
        cls = devices[comp.type]
        mount = getattr(cls, "mount_body", None)
        if mount:
            own_frame = fqn if getattr(cls, "mount_in_own_frame", False) else None
            for child in comp.components:
                out[join(fqn, child.name)] = (part(fqn, mount), own_frame)
    # a robot's component riding on another component's body (the PR2's head and arms on its torso lift)
    for robot in scene.robots:
        names = {c.name for c in robot.components}
        for name, (host, body) in cat.get("robots", robot.type).component_mounts.items():
            if name in names and host in names:
                out[join(robot.name, name)] = (part(join(robot.name, host), body), None)
    return out


def _frame(body: ET.Element) -> tuple[np.ndarray, np.ndarray]:
    """(position, rotation matrix) of a body in its parent body, from its `pos` and `quat`."""
    pos = np.array([float(v) for v in body.get("pos", "0 0 0").split()])
    quat = [float(v) for v in body.get("quat", "1 0 0 0").split()]
    return pos, quat_to_matrix(quat)


def _move_bodies(root: ET.Element, mounts: dict[str, tuple[str, str | None]]) -> None:
    parents = {child: parent for parent in root.iter() for child in parent}
    bodies = {name: b for b in root.iter("body") if (name := b.get("name")) is not None}
    for child, (target, own_frame) in mounts.items():
        if target not in bodies:
            owner = mjcf_names.owner(target)
            own = ", ".join(sorted(b for b in bodies if b != owner and mjcf_names.belongs_to(b, owner))) or "none"
            raise SceneError(f"component {owner!r}: its class mounts its children on body {target!r}, which its "
                             f"model does not have (its bodies: {own})")
        body = bodies[child]
        if own_frame is not None:
            # the mount body's pose in the component's frame, joints at zero, then the child's pose in it
            pos, rot = np.zeros(3), np.eye(3)
            chain, node = [], bodies[target]
            while node is not bodies[own_frame]:
                chain.append(node)
                node = parents[node]
            for node in reversed(chain):
                p, r = _frame(node)
                pos, rot = pos + rot @ p, rot @ r
            p, r = _frame(body)
            body.set("pos", fmt_vec(np.round(rot.T @ (p - pos), 12) + 0.0))
            body.set("quat", fmt_vec(np.round(matrix_to_quat(rot.T @ r), 12) + 0.0))
        parents[body].remove(body)
        bodies[target].append(body)
        parents[body] = bodies[target]


def _object(obj, cat: Catalogue, env) -> str:
    cls = cat.get("props", obj.type)
    color = list(obj.color) + [1.0] if len(obj.color) == 3 else list(obj.color)
    variant = cat.variant(obj.type)
    fragment = render(env, _own_template(cat, cls, cls.template), name=obj.name, id=cls.id, size=obj.size,
                      half=[s / 2 for s in obj.size], color=color, mass=obj.mass, dynamic=obj.dynamic,
                      properties=obj.properties, parts=_scaled_parts(variant, obj.size, obj.mass))
    return render(env, "mjcf/object.xml.j2", obj={
        "name": obj.name, "pos": obj.translate, "quat": euler_to_quat(*obj.rotate), "dynamic": obj.dynamic,
        "fragment": fragment, "site": bool(obj.locks and obj.dynamic)})


def _scaled_parts(variant: dict | None, size, mass: float) -> list[dict]:
    """An object of a props file: its parts (morsec.kits.layout.PropPart) scaled from the object's own size to
    the entry's `size` about its origin, each with its share of the mass (by volume) and MuJoCo's geom size."""
    if variant is None:
        return []
    scale = [s / d for s, d in zip(size, variant["size"])]
    parts = variant["parts"]
    volumes = [p.size[0] * p.size[1] * p.size[2] for p in parts]
    out = []
    for piece, volume in zip(parts, volumes):
        full = [v * k for v, k in zip(piece.size, scale)]
        geom_size = [full[0] / 2, full[2] / 2] if piece.shape == "cylinder" else [v / 2 for v in full]
        out.append({"name": piece.name, "shape": piece.shape, "pos": [v * k for v, k in zip(piece.centre, scale)],
                    "size": geom_size, "rgba": piece.rgba, "mass": mass * volume / sum(volumes)})
    return out
