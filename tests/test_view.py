"""`morsec run --view`: the web viewer is served on the bind address; the native one needs a display."""

import os
import subprocess
import sys
import urllib.request
from pathlib import Path

from runtime_helpers import Morsec, free_port, robot, scene, scene_file, wait_until

MORSEC = Path(sys.executable).with_name("morsec")


def test_native_view_without_a_display_fails_in_one_line(tmp_path):
    path = scene_file(tmp_path, scene(robot()))
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    result = subprocess.run([str(MORSEC), "run", str(path), "--view", "native", "--duration", "1",
                             "--service-port", str(free_port()), "--port-base", str(free_port())],
                            cwd=tmp_path, capture_output=True, text=True, timeout=120, env=env)
    assert result.returncode == 1
    assert result.stderr.strip().splitlines()[-1] == ("error: --view native needs a display (DISPLAY is not set); "
                                                      "use --view web, or run under Xvfb")
    assert "Traceback" not in result.stderr


def test_web_view_serves_the_model_on_localhost(tmp_path):
    port = free_port()
    with Morsec(scene_file(tmp_path, scene(robot())), tmp_path, args=("--view", "web", "--view-port", port)) as sim:
        page = wait_until(lambda: _get(f"http://127.0.0.1:{port}/"), timeout=30)  # the viewer starts in a thread
        assert b"<html" in page.lower()
        model = urllib.request.urlopen(f"http://127.0.0.1:{port}/model", timeout=20).read()
        assert len(model) > 1000  # the compiled model, served to the browser
        assert any(f"http://127.0.0.1:{port}/" in line for line in sim.stdout)
        assert _listening_addresses(port) == {"127.0.0.1"}


def _get(url: str) -> bytes | None:
    try:
        return urllib.request.urlopen(url, timeout=5).read()
    except OSError:
        return None


def _listening_addresses(port: int) -> set[str]:
    """IPv4 and IPv6 addresses with a listening TCP socket on `port` (from /proc/net/tcp*)."""
    found = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        for line in Path(table).read_text().splitlines()[1:]:
            local, state = line.split()[1], line.split()[3]
            address, hex_port = local.rsplit(":", 1)
            if int(hex_port, 16) == port and state == "0A":  # LISTEN
                if len(address) == 8:
                    found.add(".".join(str(int(address[i:i + 2], 16)) for i in (6, 4, 2, 0)))
                else:
                    found.add("::" if set(address) == {"0"} else address)
    return found
