"""MORSE's ROS test case on morsec: `from morse.testing.ros import RosTestCase`.

Importing this module makes ROS 1 importable for what the test file imports next (rospy, actionlib, the
message packages: Debian's folder appended at the end of sys.path when rospy is not importable as things
are, see morsec.middleware.ros.available), and control_msgs too (generated once into morsec's cache:
morsec.middleware.ros.messages). Without ROS it raises RosInstallationError saying what to install.

A RosTestCase is a MorseTestCase whose tests have a ROS master: the first test starts `roscore` on
$ROS_MASTER_URI's port (when no master answers there already) and it runs until the process ends. MORSE
started one per test; morsec keeps one per process because rospy keeps its registrations per process (a
subscriber made in one test is not registered again with a new master). When $ROS_MASTER_URI is not set,
it is set to a free local port, so that runs side by side do not share a master; the simulation, a child
process, inherits it. roscore's output goes to `<logs>/roscore.log`.
"""

from __future__ import annotations

import atexit
import os
import socket
import subprocess
import time
import urllib.parse
import xmlrpc.client

from morse.testing.testing import MorseTestCase, logs_folder, testlogger
from morsec.errors import MorsecError
from morsec.middleware.ros.available import require_ros
from morsec.middleware.ros.messages import ensure_messages

ROSCORE_TIMEOUT = 30.0  # s for roscore to answer


class RosInstallationError(Exception):
    """ROS 1 is not installed (MORSE's name)."""


try:
    require_ros("MORSE's ROS tests")
    ensure_messages()
except MorsecError as _err:
    raise RosInstallationError(_err.message) from None


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


if not os.environ.get("ROS_MASTER_URI"):
    os.environ["ROS_MASTER_URI"] = f"http://127.0.0.1:{_free_port()}/"
if not (os.environ.get("ROS_IP") or os.environ.get("ROS_HOSTNAME")):
    os.environ["ROS_IP"] = "127.0.0.1"  # nodes reach each other on this machine whatever its hostname resolves to


def master_online(uri: str | None = None, timeout: float = 1.0) -> bool:
    uri = uri or os.environ["ROS_MASTER_URI"]
    previous = socket.getdefaulttimeout()
    socket.setdefaulttimeout(timeout)
    try:
        return xmlrpc.client.ServerProxy(uri).getPid("/morsetesting")[0] == 1
    except (OSError, xmlrpc.client.Error):
        return False
    finally:
        socket.setdefaulttimeout(previous)


class Roscore:
    """The process's ROS master: started once, stopped at exit."""

    process: subprocess.Popen | None = None

    @classmethod
    def ensure(cls, log_folder) -> None:
        if cls.process is not None and cls.process.poll() is None:
            return
        if master_online():
            return  # one is running already (the user's, or another run's on this URI)
        port = urllib.parse.urlparse(os.environ["ROS_MASTER_URI"]).port or 11311
        log_folder.mkdir(parents=True, exist_ok=True)
        with open(log_folder / "roscore.log", "ab") as log:
            try:
                cls.process = subprocess.Popen(["roscore", "-p", str(port)], stdout=log, stderr=subprocess.STDOUT,
                                               stdin=subprocess.DEVNULL, start_new_session=True)
            except OSError as err:
                testlogger.error("Error while launching roscore! Check you can run it from the command line")
                raise RosInstallationError(f"cannot start roscore: {err}") from None
        atexit.register(cls.stop)
        deadline = time.monotonic() + ROSCORE_TIMEOUT
        while not master_online():
            if cls.process.poll() is not None or time.monotonic() > deadline:
                raise RosInstallationError(f"roscore did not start on port {port}; see {log_folder / 'roscore.log'}")
            time.sleep(0.1)

    @classmethod
    def stop(cls) -> None:
        process, cls.process = cls.process, None
        if process is None or process.poll() is not None:
            return
        process.terminate()
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()


class RosTestCase(MorseTestCase):
    """A MorseTestCase with a ROS master running (MORSE's)."""

    def setUpMw(self):
        Roscore.ensure(logs_folder(type(self)))

    def tearDownMw(self):
        """The master stays up for the next test (see the module's documentation)."""
