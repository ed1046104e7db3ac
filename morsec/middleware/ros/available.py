"""Where ROS 1's Python packages are, and the one error when they are not.

Debian installs ROS 1 (`apt-get install ros-core python3-rospy ...`) into the system Python's folder,
/usr/lib/python3/dist-packages, which a virtual environment does not see. When a scene (or a test file,
`morse.testing.ros`) needs ROS and `rospy` is not importable as things are, that folder (or the one named by
$MORSEC_ROS_PYTHONPATH) is appended at the *end* of sys.path: whatever the environment has comes first, Debian's
packages only fill in what it lacks (rospy, genpy, the message packages). Nothing happens for scenes without ROS.

Standard library only: the compiler asks this at build time without importing rospy.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import sys

from morsec.errors import MorsecError

DEBIAN_FOLDER = "/usr/lib/python3/dist-packages"
# the Python modules morsec's ROS middleware imports, and the Debian package of each
MODULES = {
    "rospy": "python3-rospy",
    "genpy": "python3-genpy",
    "genmsg": "python3-genmsg",
    "actionlib": "python3-actionlib",
    "actionlib_msgs": "python3-actionlib-msgs",
    "std_msgs": "python3-std-msgs",
    "rosgraph_msgs": "python3-rosgraph-msgs",
    "geometry_msgs": "python3-geometry-msgs",
    "sensor_msgs": "python3-sensor-msgs",
    "nav_msgs": "python3-nav-msgs",
    "trajectory_msgs": "python3-trajectory-msgs",
    "tf2_msgs": "python3-tf2-msgs",
}
# what docs/ros.md tells a user to install (roscore comes with ros-core, rostopic with python3-rostopic)
INSTALL = "apt-get install ros-core python3-rostopic " + " ".join(sorted(set(MODULES.values())))


class RosMissing(MorsecError):
    """A scene or a test asks for ROS and ROS 1 is not installed."""


def ros_folder() -> str:
    return os.environ.get("MORSEC_ROS_PYTHONPATH") or DEBIAN_FOLDER


def missing_modules() -> list[str]:
    """The ROS modules that cannot be imported, after adding the ROS folder if it was needed."""
    missing = [name for name in MODULES if not _importable(name)]
    folder = ros_folder()
    if missing and folder not in sys.path and os.path.isdir(folder):
        sys.path.append(folder)  # last: the environment's own packages keep precedence
        importlib.invalidate_caches()
        missing = [name for name in MODULES if not _importable(name)]
    return missing


def require_ros(what: str = "the ROS middleware") -> None:
    """Make ROS 1's modules importable, or raise RosMissing saying how to install them."""
    missing = missing_modules()
    if missing:
        _missing_error(what, missing)


def ros_problem(what: str = "the ROS middleware") -> str | None:
    """require_ros's message, or None when ROS is there; sys.path is left as it is (a build only asks)."""
    folder = ros_folder()
    missing = [name for name in MODULES if not _importable(name)
               and not (os.path.isdir(folder) and importlib.machinery.PathFinder.find_spec(name, [folder]))]
    if not missing:
        return None
    try:
        _missing_error(what, missing)
    except RosMissing as err:
        return err.message
    return None


def _missing_error(what: str, missing: list[str]) -> None:
    shown = ", ".join(missing[:3]) + (" ..." if len(missing) > 3 else "")
    raise RosMissing(f"{what} needs ROS 1, which is not installed ({shown} not found in this Python's path "
                     f"nor in {ros_folder()}): install it with `sudo {INSTALL}` (docs/ros.md)")


def _importable(name: str) -> bool:
    if name in sys.modules:
        return True
    try:
        return importlib.util.find_spec(name) is not None
    except (ImportError, ValueError):
        return False
