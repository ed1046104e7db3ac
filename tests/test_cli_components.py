"""`morsec components`: the catalogue, and one component's declarations, read from its class."""

import subprocess
import sys
from pathlib import Path

MORSEC = Path(sys.executable).with_name("morsec")


def morsec(*args):
    return subprocess.run([str(MORSEC), *args], capture_output=True, text=True, timeout=120)


def test_listing_names_every_kind_with_builder_names():
    out = morsec("components")
    assert out.returncode == 0
    for line in ("robots:", "sensors:", "actuators:", "environments:", "props:"):
        assert line in out.stdout.splitlines()
    assert any(line.split()[:2] == ["motion_vw", "MotionVW"] for line in out.stdout.splitlines())


def test_one_component_shows_fields_properties_levels_services_and_frequency():
    out = morsec("components", "Odometry")  # a builder name works as well as the id
    assert out.returncode == 0, out.stderr
    text = out.stdout
    assert "default frequency 60 Hz" in text
    assert "| `integrated` (default) |" in text and "| `raw` |" in text
    assert "| `dS` |" in text and "| `wz` |" in text
    assert "`get_local_data`" in text


def test_unknown_component_suggests_close_names():
    out = morsec("components", "odometri")
    assert out.returncode == 2
    assert out.stderr.strip() == "error: no component 'odometri' in the catalogue; did you mean one of 'odometry', 'Odometry'?"


def run_on_a_terminal(*args: str) -> str:
    """What `morsec ARGS` shows on a terminal (a pseudo-terminal, 100 columns)."""
    import os
    import pty
    import select
    import time
    pid, fd = pty.fork()
    if pid == 0:
        os.environ.update(COLUMNS="100", TERM="xterm-256color")
        os.environ.pop("NO_COLOR", None)
        os.execv(str(MORSEC), [str(MORSEC), *args])
    chunks, deadline = [], time.monotonic() + 120
    while time.monotonic() < deadline:
        ready, _, _ = select.select([fd], [], [], 1.0)
        if ready:
            try:
                data = os.read(fd, 65536)
            except OSError:
                break
            if not data:
                break
            chunks.append(data)
    os.waitpid(pid, 0)
    return b"".join(chunks).decode("utf-8", errors="replace")


def test_one_component_on_a_terminal_is_rendered_not_raw_markdown():
    shown = run_on_a_terminal("components", "odometry")
    assert "integrated" in shown and "get_local_data" in shown
    assert "| `integrated`" not in shown and "`get_local_data`" not in shown  # tables and code spans rendered
    assert "\x1b[" in shown  # styled: a terminal gets colour
    piped = morsec("components", "odometry").stdout
    assert "\x1b[" not in piped  # a pipe gets plain Markdown


def test_version_option_and_shell_completion():
    out = morsec("--version")
    assert out.returncode == 0 and out.stdout.startswith("morsec ") and "(MuJoCo " in out.stdout
    assert morsec("version").stdout == out.stdout
    helped = morsec("--help").stdout
    assert "--install-completion" in helped and "--show-completion" in helped
