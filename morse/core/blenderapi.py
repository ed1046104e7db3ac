"""MORSE's `morse.core.blenderapi`, the door MORSE's components went through to Blender: what morsec stands for
(the scene and its objects, the persistent storage, the logic rate, gravity, the version MORSE ran on), the rest
stopping the run with one line naming the component's line (no keyboard, renderer, textures, constraints, bpy
data here). The key codes are None, as MORSE's outside Blender."""

from __future__ import annotations

from morse.core import mathutils
from morse.core.emulation import PersistantStorage, active_world, not_emulated

__all__ = ["PersistantStorage", "getfrequency", "getssr", "gravity", "mathutils", "persistantstorage", "scene",
           "version"]

fake = False  # MORSE's flag for "outside Blender": morsec's components do run

UPARROWKEY = DOWNARROWKEY = RIGHTARROWKEY = LEFTARROWKEY = LEFTCTRLKEY = LEFTALTKEY = None
AKEY = BKEY = DKEY = EKEY = FKEY = IKEY = JKEY = KKEY = LKEY = NKEY = OKEY = QKEY = RKEY = SKEY = None
UKEY = VKEY = WKEY = XKEY = ZKEY = LEFTMOUSE = RIGHTMOUSE = F5KEY = F7KEY = F8KEY = None
CONSTRAINT_TYPE_KINEMATIC = CONSTRAINT_IK_DISTANCE = None


def scene():
    """The scene: `scene().objects` are the robots, passive objects and components, as game objects."""
    return active_world("blenderapi.scene()").scene


def persistantstorage():
    """MORSE's persistent storage: `time` (`time.time`, simulated s), `robotDict`, `componentDict`."""
    return active_world("blenderapi.persistantstorage()").storage


def getfrequency() -> float:
    """The logic rate: the main loop's frames per simulated second."""
    return active_world("blenderapi.getfrequency()").sim.clock.frequency


def gravity():
    return mathutils.Vector(active_world("blenderapi.gravity()").sim.model.opt.gravity)


def version() -> tuple[int, int, int]:
    """The Blender MORSE's components were written for (2.79): their version checks take the newer branch."""
    return (2, 79, 0)


def getssr():
    """The scene script holder: a game object holding the environment's properties."""
    return active_world("blenderapi.getssr()").script_holder


def getalwayssensors(obj) -> list:
    return []


def _refuse(name: str, why: str):
    def refused(*args, **kwargs):
        not_emulated(f"blenderapi.{name}()", why)
    refused.__name__ = name
    return refused


for _name, _why in {
    "keyboard": "no keyboard reaches a component (morsec's Keyboard actuator reads the viewer's keys)",
    "input_active": "no keyboard", "input_just_activated": "no keyboard", "input_just_released": "no keyboard",
    "input_none": "no keyboard", "joysticks": "no Blender joystick (morsec's Joystick actuator reads /dev/input)",
    "mousepointer": "no Blender window", "controller": "no logic bricks", "add_scene": "one MuJoCo scene",
    "get_scene_list": "one MuJoCo scene", "get_scene_map": "one MuJoCo scene",
    "render": "no Blender renderer (morsec's cameras render with MuJoCo)", "hascameras": "no Blender cameras",
    "initcameras": "no Blender cameras", "cameras": "no Blender cameras", "constraints": "no Bullet constraints",
    "texture": "no Blender textures", "objectdata": "no bpy data", "materialdata": "no bpy data",
    "game_settings": "no bpy data", "get_armatures": "no Blender armatures", "isfastmode": "no Blender window",
}.items():
    globals()[_name] = _refuse(_name, _why)
