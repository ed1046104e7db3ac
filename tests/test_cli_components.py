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
