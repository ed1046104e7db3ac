"""morsec's stand-in for MORSE's `morse.builder.bpymorse`, the wrapper around Blender's `bpy` that
`from morse.builder import *` handed to scripts.

    bpymorse.get_object('robot')            the Blender object of a builder object (see blender.py)
    bpymorse.get_object('Ground')           an object of MORSE's .blend environment: recorded, warned
    bpymorse.properties(obj, Type='Box')    obj.properties(Type='Box') on a builder object
    bpymorse.get_properties(obj)            the properties the script set on it

Any other bpymorse function is a Blender call: accepted, recorded in `environment.morse_only` and
warned about once, naming the script line; it returns a stand-in whose settings are recorded the same way.
"""

from __future__ import annotations

from typing import Any

from morsec.frontends.builder import session as _session
from morsec.frontends.builder.blender import BlenderObject, BlenderPath
from morsec.frontends.builder.components import EnvironmentObject

bpy = None  # MORSE's module exposed it (None outside Blender), as here


def get_object(name_or_id):
    """The Blender object named `name_or_id`: a builder object's (by its name, final name or variable),
    else an object of MORSE's Blender environment, which morsec does not have."""
    session = _session.current()
    node = _find(session, name_or_id)
    if node is not None:
        return node._bpy_object
    return environment_object(session, str(name_or_id))


def get_objects() -> list:
    """The Blender objects of the builder objects created so far."""
    session = _session.current()
    return [node._bpy_object for node in session.nodes]


def properties(obj, **kwargs) -> None:
    """Set game properties of a Blender object: a builder object's go through its `properties(...)`."""
    node = _node(obj)
    if node is not None:
        node.properties(**kwargs)
        return
    if isinstance(obj, BlenderPath):
        shown = ", ".join(f"{k}={v!r}" for k, v in kwargs.items())
        obj._record(f"{obj._path}.properties", f"bpymorse.properties({obj._shown}, {shown})", dict(kwargs))
        return
    raise _session.current().error(f"bpymorse.properties({obj!r}, ...): expected a Blender object "
                                   "(bpymorse.get_object(name) or obj._bpy_object)")


def get_properties(obj) -> dict[str, Any]:
    """The game properties the script set on a builder object (its properties and its tags)."""
    node = _node(obj)
    return dict(node._raw.get("properties", {})) if node is not None else {}


def version() -> tuple[int, int, int]:
    return (0, 0, 0)  # MORSE's answer outside Blender


def _node(obj):
    from morsec.frontends.builder.session import is_node
    if isinstance(obj, BlenderObject):
        return obj._owner
    if is_node(obj):
        return obj
    return None


def _find(session, name):
    """The builder object a Blender name designates: its final (fully-qualified) name, explicit name,
    or the variable it was named after; the first created wins."""
    name = str(name)
    for node in session.nodes + ([session.environment] if session.environment is not None else []):
        names = {node._explicit_name, node._auto_name, node._final_name}
        if session.renamed:
            names.add(node.name)
        if name in names:
            return node
    return None


def __getattr__(name: str):
    if name.startswith("_"):
        raise AttributeError(name)

    def blender_call(*args, **kwargs):
        session = _session.current()
        shown_args = ", ".join([repr(a) for a in args] + [f"{k}={v!r}" for k, v in kwargs.items()])
        shown = f"bpymorse.{name}({shown_args})"
        session.morse_only(None, f"bpymorse.{name}", {"args": list(args), **kwargs},
                           "is a Blender call with no meaning in morsec", shown=shown)
        return BlenderPath(session, None, f"bpymorse.{name}()", f"bpymorse.{name}(...)",
                           "is a Blender setting with no meaning in morsec")

    blender_call.__name__ = name
    return blender_call


def environment_object(session, name: str) -> BlenderPath:
    """`bpymorse.get_object(name)` for a name that no builder object has: an object the environment holds
    (indoors-1/boxes' RedBox), which then becomes the script's to set; else an object of MORSE's .blend."""
    env = session.environment
    env_id = env._raw.get("name") if env is not None else None
    cat = session.catalogue
    resolved = cat.resolve("environments", env_id) if isinstance(env_id, str) else None
    held = {o["name"]: o for o in cat.get("environments", resolved).objects} if resolved else {}
    if name in held:
        return EnvironmentObject(held[name])._bpy_object
    return BlenderPath(session, None, str(name), f"bpymorse.get_object({name!r})",
                       f": {name!r} is an object of MORSE's Blender environment file, which morsec does not load")
