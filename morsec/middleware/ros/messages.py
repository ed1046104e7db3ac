"""The ROS 1 messages Debian does not package (control_msgs: the PR2's controllers, MORSE's armature
overlay), generated to Python with Debian's genpy from morsec's own definitions (definitions/), into the
user's cache folder, and made importable as `control_msgs.msg`, in the simulation and in test files alike.

    $XDG_CACHE_HOME/morsec/ros-messages/<hash>/control_msgs/msg/_JointTrajectoryControllerState.py ...

The hash covers the definitions and the genpy that generated them: a change of either makes a new folder.
The definitions' dependencies (std_msgs/Header, trajectory_msgs/JointTrajectory, actionlib_msgs/GoalID ...)
are read from the installed message modules (their `_full_text`), so the md5sums are those every ROS node
computes. A package an environment already provides (a ROS installation with control_msgs) is left alone.
"""

from __future__ import annotations

import hashlib
import importlib
import os
import shutil
import sys
import tempfile
from pathlib import Path

from morsec.middleware.ros.available import require_ros

DEFINITIONS = Path(__file__).resolve().parent / "definitions"
CACHE = "morsec/ros-messages"  # under $XDG_CACHE_HOME or ~/.cache
SEPARATOR = "=" * 80
# actionlib's seven messages of an action, from its goal, result and feedback (genaction's expansion)
ACTION_MESSAGES = {
    "Action": "{name}ActionGoal action_goal\n{name}ActionResult action_result\n{name}ActionFeedback action_feedback\n",
    "ActionGoal": "Header header\nactionlib_msgs/GoalID goal_id\n{name}Goal goal\n",
    "ActionResult": "Header header\nactionlib_msgs/GoalStatus status\n{name}Result result\n",
    "ActionFeedback": "Header header\nactionlib_msgs/GoalStatus status\n{name}Feedback feedback\n",
}
# the installed messages the definitions use (with theirs, from their full text)
DEPENDENCIES = ("std_msgs.msg:Header", "trajectory_msgs.msg:JointTrajectory",
                "trajectory_msgs.msg:JointTrajectoryPoint", "actionlib_msgs.msg:GoalID",
                "actionlib_msgs.msg:GoalStatus")


def packages() -> list[str]:
    return sorted(p.name for p in DEFINITIONS.iterdir() if p.is_dir())


def ensure_messages() -> Path:
    """Make every package of definitions/ importable (generated once into the cache); return the folder
    added to sys.path. RosMissing when ROS 1 is not installed."""
    require_ros("ROS messages")
    import genpy

    sources = _sources()
    digest = hashlib.sha256(repr((sorted(sources.items()), genpy.__file__, _genpy_version())).encode()).hexdigest()
    folder = _cache_root() / digest[:16]
    if not (folder / "complete").is_file():
        _generate(sources, folder)
    if str(folder) not in sys.path:
        # after the environment's own folders: a real control_msgs installed there wins
        sys.path.append(str(folder))
        importlib.invalidate_caches()
    return folder


def _sources() -> dict[str, str]:
    """{package/kind/Name.ext: text} of every definition."""
    out = {}
    for path in sorted(DEFINITIONS.glob("*/*/*")):
        if path.suffix in (".msg", ".action"):
            out[str(path.relative_to(DEFINITIONS))] = path.read_text(encoding="utf-8")
    return out


def _messages(sources: dict[str, str]) -> dict[str, str]:
    """{package/Name: .msg text}: the .msg files and the seven messages of each .action."""
    out = {}
    for key, text in sources.items():
        package, kind, filename = key.split("/")
        name, _, ext = filename.rpartition(".")
        if ext == "msg":
            out[f"{package}/{name}"] = text
            continue
        parts = [part.strip("\n") for part in text.split("\n---")]
        if len(parts) != 3:
            raise ValueError(f"{key}: an action has a goal, a result and a feedback separated by '---'")
        for suffix, part in zip(("Goal", "Result", "Feedback"), parts):
            out[f"{package}/{name}{suffix}"] = part.strip() + "\n" if part.strip() else ""
        for suffix, template in ACTION_MESSAGES.items():
            out[f"{package}/{name}{suffix}"] = template.format(name=name)
    return out


def _generate(sources: dict[str, str], folder: Path) -> None:
    from genmsg import MsgContext
    from genmsg.msg_loader import load_msg_from_string
    from genpy.generate_initpy import write_modules
    from genpy.generator import msg_generator

    context = MsgContext.create_default()
    for ref in DEPENDENCIES:
        module, _, cls = ref.partition(":")
        full_text = getattr(importlib.import_module(module), cls)._full_text
        first = f"{module.split('.')[0]}/{cls}"
        for section in _sections(first, full_text):
            full_name, text = section
            if not context.is_registered(full_name):
                context.register(full_name, load_msg_from_string(context, text, full_name))
    messages = _messages(sources)
    specs = {}
    for full_name, text in messages.items():
        specs[full_name] = load_msg_from_string(context, text, full_name)
        context.register(full_name, specs[full_name])
    folder.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=".generating-", dir=folder.parent))
    try:
        for full_name, spec in specs.items():
            package, name = full_name.split("/")
            out = staging / package / "msg"
            out.mkdir(parents=True, exist_ok=True)
            (staging / package / "__init__.py").write_text("", encoding="utf-8")
            code = "\n".join(msg_generator(context, spec, {}))
            (out / f"_{name}.py").write_text(code, encoding="utf-8")
        for package in {name.split("/")[0] for name in specs}:
            write_modules(str(staging / package / "msg"))
        (staging / "complete").write_text("", encoding="utf-8")
        try:
            os.rename(staging, folder)
        except OSError:  # another process generated it meanwhile
            if not (folder / "complete").is_file():
                raise
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def _sections(first: str, full_text: str) -> list[tuple[str, str]]:
    """A message's full text -> [(package/Name, its own text)], itself first, then its dependencies."""
    out = []
    for k, chunk in enumerate(full_text.split(SEPARATOR)):
        chunk = chunk.strip("\n")
        if k == 0:
            out.append((first, chunk + "\n"))
            continue
        head, _, body = chunk.partition("\n")
        out.append((head.removeprefix("MSG: ").strip(), body + "\n"))
    return out


def _cache_root() -> Path:
    cache = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(cache) / CACHE


def _genpy_version() -> str:
    try:
        from importlib.metadata import version
        return version("genpy")
    except Exception:
        return "unknown"
