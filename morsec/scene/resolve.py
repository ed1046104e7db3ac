"""After validation: canonical type ids, names (MORSE rules), default interfaces, levels and frequencies
written out, so that the IR records exactly what will run."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NoReturn

from morsec.component.catalogue import Catalogue, modifier_class, type_lineage
from morsec.errors import SceneError, did_you_mean, yaml_path
from morsec.middleware.base import StreamRequest
from morsec.middleware.registry import middleware as middleware_class
from morsec.middleware.registry import service_middlewares
from morsec.scene.models import StreamSpec, StreamSpecBase
from morsec.scene.naming import assign_names, type_name
from morsec.scene.sourcemap import SourceMap
from morsec.scene.walk import walk_children


def add_robot_defaults(data: Any, cat: Catalogue) -> None:
    """Before validation: append each robot type's `default_components` the scene does not name itself."""
    import copy
    if not isinstance(data, dict) or not isinstance(data.get("robots"), list):
        return
    for robot in data["robots"]:
        if not isinstance(robot, dict) or not isinstance(robot.get("type"), str):
            continue
        rid = cat.resolve("robots", robot["type"])
        defaults = cat.get("robots", rid).default_components if rid else ()
        if not defaults:
            continue
        components = robot.setdefault("components", [])
        if not isinstance(components, list):
            continue
        named = {c.get("name") or c.get("type") for c in components if isinstance(c, dict)}
        without = robot.get("without")
        named |= set(without) if isinstance(without, list) and all(isinstance(n, str) for n in without) else set()
        components.extend(_scene_entry(copy.deepcopy(c)) for c in defaults if c["name"] not in named)


def _scene_entry(spec: dict) -> dict:
    """A default component as a scene entry: without `attribute` (the builder's name for it on the robot)."""
    spec.pop("attribute", None)
    for child in spec.get("components", ()):
        _scene_entry(child)
    return spec


def add_environment_objects(data: Any, cat: Catalogue) -> Any:
    """Before validation: the scene data with the environment type's `objects` that the scene does not name
    itself appended to its own (a new mapping: the scene as written, which `convert` writes, keeps only
    what it says)."""
    import copy
    if not isinstance(data, dict):
        return data
    env = data.get("environment", {})
    name = env.get("name", "empty") if isinstance(env, dict) else None
    eid = cat.resolve("environments", name) if isinstance(name, str) else None
    held = cat.get("environments", eid).objects if eid else ()
    objects = data.get("objects", [])
    if not held or not isinstance(objects, list):
        return data
    named = {o.get("name") or o.get("type") for o in objects if isinstance(o, dict)}
    return {**data, "objects": objects + [copy.deepcopy(o) for o in held if o["name"] not in named]}


def add_prop_defaults(data: Any, cat: Catalogue) -> Any:
    """Before validation: each object entry completed with its prop type's `defaults` (a new mapping, as
    add_environment_objects: the scene as written keeps only what it says)."""
    import copy
    if not isinstance(data, dict) or not isinstance(data.get("objects"), list):
        return data
    objects, changed = [], False
    for obj in data["objects"]:
        ptype = obj.get("type") if isinstance(obj, dict) else None
        defaults = cat.prop_defaults(ptype) if isinstance(ptype, str) else {}
        if defaults:
            own = copy.deepcopy(defaults)
            if isinstance(obj.get("properties"), dict):
                obj = {**obj, "properties": {**own.get("properties", {}), **obj["properties"]}}
            obj, changed = {**own, **obj}, True
        objects.append(obj)
    return {**data, "objects": objects} if changed else data


def resolve(scene: Any, cat: Catalogue, smap: SourceMap | None = None) -> None:
    def fail(path: tuple, message: str) -> NoReturn:
        pos = smap.find(path) if smap else None
        line, col = pos if pos else (None, None)
        raise SceneError(f"{yaml_path(path)}: {message}", smap.file if smap else None, line, col)

    for robot in scene.robots:
        robot.type = cat.resolve("robots", robot.type)
    for obj in scene.objects:
        if cat.variant(obj.type) is None:  # an object of a props file keeps its name: it says which
            obj.type = cat.resolve("props", obj.type)

    top = list(scene.robots) + list(scene.objects)
    paths = [("robots", i) for i in range(len(scene.robots))] + [("objects", i) for i in range(len(scene.objects))]
    assign_names(top, default=lambda e: e.type,
                 on_duplicate=lambda i, name: fail(paths[i] + ("name",), f"duplicate name {name!r}: robots and "
                                                   "objects share one namespace; rename one of them"))
    assign_names(scene.zones, default=lambda z: z.type,
                 on_duplicate=lambda i, name: fail(("zones", i, "name"), f"duplicate zone name {name!r}"))

    env_properties = scene.environment.properties
    for r, robot in enumerate(scene.robots):
        _check_tags(robot, cat.get("robots", robot.type), ("robots", r), fail)
        _check_without(robot, cat.get("robots", robot.type), ("robots", r), fail)
        _resolve_children(robot.components, ("robots", r), robot.default_interface, cat, fail, env_properties)
        _check_robot_requirements(robot, ("robots", r), cat, fail)

    for k, middleware in enumerate(scene.environment.services):
        _check_available(middleware, ("environment", "services", k), fail)
    if scene.environment.multinode is not None:
        _check_multinode(scene.environment.multinode, [robot.name for robot in scene.robots], fail)


def _check_multinode(multinode, robot_names: list[str], fail) -> None:
    """configure_multinode: the socket protocol, and every robot of the scene on exactly one node."""
    where = ("environment", "multinode")
    if multinode.protocol == "hla":
        fail(where + ("protocol",), "protocol 'hla' needs an HLA run-time infrastructure (CERTI with PyHLA), which "
             "cannot be installed here; use protocol 'socket' (the default) with `morsec multinode-server`")
    owner: dict[str, str] = {}
    for node, names in multinode.distribution.items():
        for j, name in enumerate(names):
            if name not in robot_names:
                fail(where + ("distribution", node, j),
                     f"multinode node {node!r} lists robot {name!r}, which is not in the scene")
            if name in owner:
                fail(where + ("distribution", node, j), f"robot {name!r} is on two nodes, {owner[name]!r} and "
                     f"{node!r}: each robot is simulated by one node")
            owner[name] = node
    unassigned = [name for name in robot_names if name not in owner]
    if unassigned:
        nodes = ", ".join(multinode.distribution) or "none yet"
        several = len(unassigned) > 1
        fail(where + ("distribution",), f"robot{'s' if several else ''} {', '.join(map(repr, unassigned))} "
             f"{'are' if several else 'is'} on no node: list each robot under the node that simulates it "
             f"(nodes: {nodes})")


def _resolve_children(components: list, parent_path: tuple, default_interface: str | None, cat: Catalogue, fail,
                      env_properties: dict):
    for c in components:
        c.type = cat.resolve("sensors", c.type) or cat.resolve("actuators", c.type)
    assign_names(components, default=lambda c: type_name(c.type),
                 on_duplicate=lambda i, name: fail(parent_path + ("components", i, "name"),
                                                   f"duplicate component name {name!r} under the same parent"))
    devices = cat.devices()
    for i, comp in enumerate(components):
        cls = devices[comp.type]
        _check_tags(comp, cls, parent_path + ("components", i), fail)
        if comp.level is None:
            comp.level = cls.default_level()
        if comp.frequency is None:
            comp.frequency = float(cls.frequency)
        for middleware in comp.interfaces:
            _add_stream(comp, cls, middleware)
            _add_service(comp, middleware)
        if default_interface:
            # a component the middleware has no message for is left out (ROS: a thermometer), as named ones
            # are refused below
            if not comp.streams and not middleware_class(default_interface).check_stream(StreamRequest(
                    comp.name or type_name(comp.type), cls.direction, {}, type_lineage(cls),
                    comp.properties.model_dump(mode="json"))):
                _add_stream(comp, cls, default_interface)
            if not comp.services:
                _add_service(comp, default_interface)
        here = parent_path + ("components", i)
        types = type_lineage(cls)
        for k, stream in enumerate(comp.streams):
            if stream.direction is None:
                stream.direction = cls.direction
            _check_available(stream.middleware, here + ("streams", k), fail)
            _check_stream_options(stream, here + ("streams", k), fail)
            request = StreamRequest(comp.name, stream.direction, stream.model_dump(
                exclude_none=True, exclude={"middleware", "direction"}), types, comp.properties.model_dump(mode="json"))
            problem = middleware_class(stream.middleware).check_stream(request)
            if problem:
                fail(here + ("streams", k), problem)
        for k, middleware in enumerate(comp.services):
            _check_available(middleware, here + ("services", k), fail)
        for k, overlay in enumerate(comp.overlays):
            _check_available(overlay.middleware, here + ("overlays", k), fail)
            try:
                middleware_class(overlay.middleware).overlay_class(overlay.overlay, types)
            except ValueError as err:
                fail(here + ("overlays", k, "overlay"), str(err))
        for m, modifier in enumerate(comp.modifiers):
            _check_modifier(modifier, cls, parent_path + ("components", i, "modifiers", m), fail, env_properties,
                            cat)
        _resolve_children(comp.components, parent_path + ("components", i), default_interface, cat, fail,
                          env_properties)


def _check_available(middleware: str, path: tuple, fail) -> None:
    """A middleware this machine cannot run (ROS not installed) stops the build, saying what to install."""
    problem = middleware_class(middleware).unavailable()
    if problem:
        fail(path, problem)


def _check_without(robot, cls, path: tuple, fail) -> None:
    """`without` names components the robot type carries (default_components), nothing else."""
    carried = [c["name"] for c in cls.default_components]
    for k, name in enumerate(robot.without):
        if name not in carried:
            fail(path + ("without", k), f"robot type {cls.id!r} carries no component {name!r} to leave out"
                 + ((did_you_mean(name, carried) or f" (it carries {', '.join(carried)})") if carried
                    else " (it carries none)"))


def _check_tags(entry, cls, path: tuple, fail) -> None:
    """A tag is a game property the type does not declare: a declared one belongs under `properties`."""
    for key in entry.tags:
        if key in cls.Properties.model_fields:
            fail(path + ("tags", key), f"{key!r} is a property of {cls.kind} type {cls.id!r}: set it under "
                 "'properties' (tags are the game properties a type does not declare)")


def _check_stream_options(stream, path: tuple, fail) -> None:
    """An option that only another middleware reads (a `port` on a text stream) is an error, not ignored."""
    declared = tuple(middleware_class(stream.middleware).Options.model_fields)
    for option in sorted(stream.model_dump(exclude_none=True)):
        if option not in StreamSpecBase.model_fields and option not in declared:
            fail(path + (option,), f"{stream.middleware} streams have no option {option!r}"
                 + (f" (they take: {', '.join(declared)})" if declared else ""))


def _check_robot_requirements(robot, path: tuple, cat: Catalogue, fail) -> None:
    """A component that reads robot class attributes (wheel joints, steering) needs a robot declaring them."""
    robot_cls = cat.get("robots", robot.type)
    devices = cat.devices()
    for placed in walk_children(robot, robot.components, robot.name, path):
        comp = placed.component
        needs = devices[comp.type].robot_requires
        missing = [a for a in needs if not hasattr(robot_cls, a)]
        if missing:
            fitting = [rid for rid, rc in sorted(cat.by_kind.get("robots", {}).items())
                       if all(hasattr(rc, a) for a in needs)]
            fail(placed.path + ("type",),
                 f"{comp.type!r} needs a robot declaring {', '.join(needs)}; robot type {robot.type!r} does not"
                 + (f" (these do: {', '.join(fitting)})" if fitting else ""))


def _check_modifier(modifier, cls, path: tuple, fail: Callable[[tuple, str], NoReturn], env_properties: dict,
                    cat: Catalogue) -> None:
    from pydantic import ValidationError

    impl = modifier_class(modifier.name, cls)
    if impl is None:
        fail(path + ("name",), f"modifier {modifier.name!r} does not apply to {cls.id!r} "
                               f"(it applies to: {', '.join(cat.applies_to(modifier.name)) or 'no component'})")
    missing = [k for k in ("longitude", "latitude", "altitude") if k not in env_properties]
    if impl.needs_geo and missing:
        fail(path + ("name",), f"modifier {modifier.name!r} needs the environment properties longitude, latitude "
                               f"and altitude (missing: {', '.join(missing)})")
    try:
        impl.Params.model_validate(modifier.model_extra or {})
    except ValidationError as err:
        e = err.errors(include_url=False)[0]
        key = e["loc"][0] if e["loc"] else None
        where = path + ((key,) if key is not None else ())
        fail(where, f"modifier {modifier.name!r}: {f'{key}: ' if key else ''}{e['msg']}")


def _add_stream(comp, cls, middleware: str) -> None:
    if cls.exportable and not any(s.middleware == middleware for s in comp.streams):
        comp.streams.append(StreamSpec(middleware=middleware))


def _add_service(comp, middleware: str) -> None:
    if middleware in service_middlewares() and middleware not in comp.services:
        comp.services.append(middleware)
