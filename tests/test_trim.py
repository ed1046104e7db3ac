"""morsec.runtime.trim is compiled by mypyc when the package is installed (pyproject.toml): the compiled module
and its source, run by the interpreter, give the same floats to the bit, call after call."""

from __future__ import annotations

import importlib.util
import math
import os
from pathlib import Path

import numpy as np
import pytest

from morsec.kits.geometry import euler_to_quat, quat_to_matrix
from morsec.runtime import trim as compiled

SOURCE = Path(compiled.__file__).with_name("trim.py")
STALE = ("the compiled module differs from trim.py run as it is: trim.py changed since the package was installed "
         "(pip install -e . again), or the C compiler fused multiplications and additions (hatch_build.py)")


def interpreted_module():
    spec = importlib.util.spec_from_file_location("trim_interpreted", SOURCE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


interpreted = interpreted_module()


def test_the_installed_module_is_the_compiled_one():
    assert Path(compiled.__file__).suffix != ".py", (
        "morsec.runtime.trim runs interpreted: install the package (pip install -e .) to compile it")
    assert Path(interpreted.__file__).suffix == ".py"


def rotation(rng) -> list[float]:
    return quat_to_matrix(euler_to_quat(*rng.uniform(-np.pi, np.pi, 3))).reshape(-1).tolist()


def same_bits(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    """Equal, and zeros of the same sign (== says 0.0 == -0.0)."""
    return a == b and all(math.copysign(1.0, x) == math.copysign(1.0, y) for x, y in zip(a, b))


@pytest.mark.parametrize("heading", [True, False])
def test_mean_velocity_compiled_is_interpreted_to_the_bit(heading):
    rng = np.random.default_rng(11)
    for k in range(2000):
        rot0 = rotation(rng)
        rot1 = list(rot0) if k % 4 == 0 else rotation(rng)  # no turn at all: the sin == 0 branch
        pos0, pos1 = rng.normal(size=3).tolist(), rng.normal(size=3).tolist()
        dt = float(rng.uniform(0.001, 0.1))
        assert same_bits(compiled.mean_velocity(pos0, rot0, pos1, rot1, dt, heading),
                         interpreted.mean_velocity(pos0, rot0, pos1, rot1, dt, heading)), STALE


@pytest.mark.parametrize("heading", [True, False])
def test_following_a_command_compiled_is_interpreted_to_the_bit(heading):
    """A robot driven along a noisy path by commands held a few calls, changed, reversed (the trim reset along
    an axis), sometimes given as ints, at the same time twice (dt 0: no correction), with settle 0, 1, 2 and 10:
    each call drives the robot with the same floats, both keep the same trims, and the trims are corrected."""
    rng = np.random.default_rng(5)
    ours, theirs = compiled.Follow(), interpreted.Follow()
    time, pos, angles = 0.0, [0.0, 0.0, 0.1], np.zeros(3)
    command: tuple = (0.5, 0.0, 0.3)
    for settle, held in [(0, 7), (1, 7), (2, 7), (10, 23)]:  # held: calls a command is held
        corrected = 0
        for k in range(1000):
            if k % held == 0:
                command = tuple(float(c) for c in rng.choice([-1.0, 0.0, 0.4, 1.5], 3) * rng.uniform(0.5, 1.5, 3))
                if k % 10 == 0:
                    command = (1, 0, -1)  # as a client's JSON may give them
            if k % 13 != 0:
                time += 1 / 60
            pos = [p + float(d) for p, d in zip(pos, rng.normal(0.0, 0.01, 3))]
            angles = angles + rng.normal(0.0, 0.02, 3)
            rot = quat_to_matrix(euler_to_quat(*angles)).reshape(-1).tolist()
            trim_before = ours.trim
            ours_drive = ours.drive(*command, time, pos, rot, 0.25, settle, heading)
            theirs_drive = theirs.drive(*command, time, pos, rot, 0.25, settle, heading)
            assert same_bits(ours_drive, theirs_drive), f"settle {settle}, call {k}: {STALE}"
            assert same_bits(ours.trim, theirs.trim) and ours.held == theirs.held, f"settle {settle}, call {k}: {STALE}"
            corrected += ours.held > 0 and ours.trim != trim_before
        assert corrected > 100, settle  # the trims were corrected, not only reset


def test_a_trim_is_dropped_along_an_axis_where_the_command_reverses():
    follow = compiled.Follow()
    rot = np.eye(3).reshape(-1).tolist()
    for k in range(4):  # held, the robot standing still: the trim grows towards the command
        follow.drive(1.0, 0.0, 0.5, k / 60, [0.0, 0.0, 0.0], rot, 0.25, 2, True)
    t0, _, t2 = follow.trim
    assert t0 > 0.0 and t2 > 0.0
    assert follow.drive(-1.0, 0.0, 0.5, 4 / 60, [0.0, 0.0, 0.0], rot, 0.25, 2, True) == (-1.0, 0.0, 0.5 + t2)
    assert follow.held == 0 and follow.trim == (0.0, 0.0, t2)


def test_a_command_followed_must_be_finite_numbers(tmp_path):
    """RobotHandle.follow (motion_vw_diff's, a lab's own actuator's) refuses NaN and infinities: compiled and
    interpreted would tell a NaN command held from a new one differently (a NaN is not equal to itself)."""
    from morsec.testing import simulate

    scene = {"environment": {"name": "empty"}, "robots": [{"name": "r", "type": "atrv"}]}
    with simulate(scene, tmp_path) as sim:
        robot = sim.sim.robots[0].handle
        assert robot.follow("mine", [1, 0, 0]) == (1.0, 0.0, 0.0)  # ints taken as floats
        for bad in (float("nan"), float("inf")):
            with pytest.raises(ValueError, match="mine: a command must be finite numbers"):
                robot.follow("mine", [0.5, 0.0, bad])


def test_a_compiled_module_older_than_its_source_is_said_on_the_log(tmp_path, caplog):
    from types import SimpleNamespace

    from morsec.runtime.robot import warn_if_stale

    compiled_file, source = tmp_path / "trim.cpython-311-x86_64-linux-gnu.so", tmp_path / "trim.py"
    compiled_file.write_bytes(b"")
    source.write_text("")
    module = SimpleNamespace(__file__=str(compiled_file), __name__="morsec.runtime.trim")
    os.utime(compiled_file, (1_000_000, 1_000_000))
    os.utime(source, (1_000_001, 1_000_001))  # installed together: a second apart at most
    assert not warn_if_stale(module)
    os.utime(source, (1_000_060, 1_000_060))  # edited, pulled or merged a minute later
    with caplog.at_level("WARNING", logger="morsec.robot"):
        assert warn_if_stale(module)
    assert "changed after it was compiled" in caplog.text and "pip install -e ." in caplog.text
    assert not warn_if_stale(SimpleNamespace(__file__=str(source), __name__="morsec.runtime.trim"))  # interpreted
