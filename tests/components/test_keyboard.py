"""keyboard: keys held in the web viewer drive the robot, through the viewer's real socket; headless, the
keyboard warns once and the robot stays where it is."""

from __future__ import annotations

import struct
import threading
import time

import pytest
from runtime_helpers import Morsec, free_port, pose_sensor, robot, scene, scene_file, wait_until
from websockets.sync.client import connect

# MuJoCo Studio's web viewer takes the browser's keyboard and mouse through NetImgui (1.13, protocol 18), its
# /ui socket bridged to the viewer's headless ImGui: the browser sends CmdVersion (120 bytes), reads the
# viewer's, then sends CmdInput (616 bytes) with the keys down as a bit mask (NetImgui's own key numbers).
NETIMGUI_VERSION = 18
CMD_VERSION, CMD_INPUT = 0, 2
INPUT_SIZE, KEYS_DOWN_AT = 616, 560
UP_ARROW = 3


class BrowserKeys:
    """What the browser page does on Studio's /ui socket, reduced to holding keys down."""

    def __init__(self, ws):
        self.ws = ws
        version = bytearray(120)
        struct.pack_into("<IB", version, 0, 120, CMD_VERSION)
        version[8:12] = b"test"
        struct.pack_into("<IIIB", version, 104, NETIMGUI_VERSION, 0, 0, 2)  # ImWchar is 2 bytes
        self.ws.send(bytes(version))
        answer = self.ws.recv(timeout=20)
        assert struct.unpack_from("<I", answer, 104)[0] == NETIMGUI_VERSION, "the viewer's NetImgui changed"
        self._open = True
        # the viewer streams its UI back: read it so that it never waits on us
        threading.Thread(target=self._drain, daemon=True).start()

    def _drain(self) -> None:
        while self._open:
            try:
                self.ws.recv(timeout=0.2)
            except TimeoutError:
                continue
            except Exception:
                return

    def hold(self, keys: set[int], seconds: float) -> None:
        command = bytearray(INPUT_SIZE)
        struct.pack_into("<IB", command, 0, INPUT_SIZE, CMD_INPUT)
        struct.pack_into("<HH", command, 8, 800, 600)  # the page's size
        struct.pack_into("<ff", command, 540, 1.0, 30.0)  # font scale, frames per second
        mask = sum(1 << k for k in keys)
        struct.pack_into("<QQQ", command, KEYS_DOWN_AT, mask & (2**64 - 1), mask >> 64, 0)
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.ws.send(bytes(command))
            time.sleep(0.03)

    def close(self) -> None:
        self._open = False


def keyboard_robot(control: str = "Position") -> dict:
    return robot("robot", pose_sensor(), {"name": "keyboard", "type": "keyboard",
                                          "properties": {"Speed": 2.0, "ControlType": control}})


def x_of(sim: Morsec) -> float:
    with sim.stream("robot.pose") as pose:
        pose.drain()
        return float(pose.json()["x"])


@pytest.mark.parametrize("control", ["Position", "Velocity"])
def test_up_arrow_held_in_the_web_viewer_drives_the_robot(tmp_path, control):
    port = free_port()
    path = scene_file(tmp_path, scene(keyboard_robot(control), strategy="best_effort"))
    with Morsec(path, tmp_path, args=("--view", "web", "--view-port", port)) as sim:
        wait_until(lambda: _serving(port), timeout=30)
        assert abs(x_of(sim)) < 0.01
        with connect(f"ws://127.0.0.1:{port}/ui?sid=test", max_size=None, open_timeout=20) as ws:
            browser = BrowserKeys(ws)
            try:
                browser.hold({UP_ARROW}, 2.0)
                moving = x_of(sim)
                browser.hold(set(), 0.5)  # released
                stopped = x_of(sim)
                time.sleep(1.0)
                still = x_of(sim)
            finally:
                browser.close()
    # 2 m/s forward while the key was down (the wall clock's 2 s, give or take the viewer's frames)
    assert 3.0 < moving < 5.0
    assert stopped == pytest.approx(still, abs=0.02 if control == "Position" else 0.1)
    assert stopped < moving + 1.3


def test_headless_keyboard_warns_once_and_does_nothing(tmp_path):
    path = scene_file(tmp_path, scene(keyboard_robot()))
    with Morsec(path, tmp_path) as sim:
        start = x_of(sim)
        time.sleep(1.0)
        assert x_of(sim) == pytest.approx(start, abs=1e-6)
        sim.stop()
        warnings = [line for line in sim.output().splitlines() if "no viewer to read keys from" in line]
    assert len(warnings) == 1
    assert "robot.keyboard" in warnings[0] and "--view web" in warnings[0]


def _serving(port: int) -> bool:
    import socket
    try:
        socket.create_connection(("127.0.0.1", port), 0.5).close()
        return True
    except OSError:
        return False
