"""MORSE's test framework, shipped: a MORSE user's test file runs as `python my_test.py` (and under pytest)
with `from morse.testing.testing import MorseTestCase, main` and `from morse.builder import *`.

The test files below are written for these tests in MORSE's style. Each runs in a network namespace of its
own when `unshare -n` works here, since MORSE's tests use the fixed ports 4000 and 60000+."""

from __future__ import annotations

import functools
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

pytest.importorskip("pymorse")

TIMEOUT = 240


@functools.cache
def isolated() -> bool:
    try:
        return subprocess.run(["unshare", "-n", "sh", "-c", "ip link set lo up"], capture_output=True,
                              timeout=10).returncode == 0
    except (OSError, subprocess.TimeoutExpired):
        return False


def run_python(args: list[str], cwd: Path, **env: str) -> subprocess.CompletedProcess:
    cmd = [sys.executable, *args]
    if isolated():
        cmd = ["unshare", "-n", "sh", "-c", 'ip link set lo up && exec "$@"', "sh", *cmd]
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=TIMEOUT,
                          env={**os.environ, **env}, stdin=subprocess.DEVNULL)


POSE_TEST = '''
    #! /usr/bin/env python
    """Reads a robot's pose over the socket middleware, as MORSE's base tests do."""
    import os

    from morse.testing.testing import MorseTestCase
    from pymorse import Morse

    try:
        from morse.builder import *
    except ImportError:
        pass

    EXPECTED_X = float(os.environ.get("EXPECTED_X", "1.0"))


    class ReadPoseTest(MorseTestCase):
        def setUpEnv(self):
            robot = ATRV()
            robot.translate(x=1.0)
            pose = Pose()
            pose.add_stream('socket')
            robot.append(pose)
            env = Environment('empty', fastmode=True)
            env.add_service('socket')

        def remember_simulation(self):
            with open(os.environ["PIDS_FILE"], "a") as pids:
                pids.write(f"{self.pid}\\n")

        def test_a_pose_where_the_robot_stands(self):
            self.remember_simulation()
            with Morse() as morse:
                self.assertEqual(set(morse.streams()), {"robot.pose"})
                pose = morse.robot.pose.get()
            self.assertAlmostEqual(pose["x"], EXPECTED_X, delta=0.05)
            self.assertAlmostEqual(pose["y"], 0.0, delta=0.05)

        def test_b_one_simulation_per_test(self):
            self.remember_simulation()
            with open(os.environ["PIDS_FILE"]) as pids:
                before = [int(line) for line in pids.read().split()][:-1]
            self.assertTrue(before)
            for pid in before:
                self.assertNotEqual(pid, self.pid)
                self.assertFalse(os.path.exists(f"/proc/{pid}"), f"simulation {pid} outlived its test")


    if __name__ == "__main__":
        from morse.testing.testing import main
        main(ReadPoseTest)
'''

BROKEN_TEST = '''
    from morse.testing.testing import MorseBuilderFailureTestCase, MorseTestCase, main
    from morse.builder import *


    class BrokenSceneTest(MorseTestCase):
        def setUpEnv(self):
            robot = ATRV()
            robot.append(NoSuchSensor())
            env = Environment('empty')

        def test_never_reached(self):
            pass


    class RefusedSceneTest(MorseBuilderFailureTestCase):
        def setUpEnv(self):
            robot = ATRV()
            robot.name = "a.b"
            env = Environment('empty')

        def test_refused(self):
            pass


    class AcceptedSceneTest(MorseBuilderFailureTestCase):
        def setUpEnv(self):
            robot = ATRV()
            env = Environment('empty')

        def test_accepted(self):
            pass


    if __name__ == "__main__":
        main(BrokenSceneTest, RefusedSceneTest, AcceptedSceneTest, time_modes=[TimeStrategies.FixedSimulationStep])
'''


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(textwrap.dedent(text).lstrip(), encoding="utf-8")
    return path


def pids_of(path: Path) -> list[int]:
    return [int(line) for line in path.read_text().split()]


def gone(pid: int) -> bool:
    return not os.path.exists(f"/proc/{pid}")


@pytest.fixture
def pose_test(tmp_path):
    folder = tmp_path / "tests"
    folder.mkdir()
    return write(folder, "pose_testing.py", POSE_TEST)


def test_a_morse_test_file_passes_under_both_time_strategies(pose_test, tmp_path):
    pids, logs = tmp_path / "pids", tmp_path / "logs"
    done = run_python([pose_test.name], pose_test.parent, PIDS_FILE=str(pids), MORSE_TEST_LOGS=str(logs))
    out = done.stdout + done.stderr
    assert done.returncode == 0, out
    # MORSE's runner: a time-mode switch, then every test, per strategy; unittest's verbose lines
    assert len(re.findall(r"^test_switch \(.*\) \.\.\. ok$", out, re.M)) == 2, out
    assert re.search(r"^Ran 6 tests", out, re.M) and out.rstrip().endswith("OK"), out
    assert out.index("in Best Effort") < out.index("in Fixed Simulation Step")
    # four simulations, each gone when its test ended (test_b checks the ones before it)
    started = pids_of(pids)
    assert len(started) == len(set(started)) == 4 and all(gone(pid) for pid in started)
    log = (logs / "ReadPoseTest.log").read_text()
    assert log.count("SCENE INITIALIZED") == 4 and log.count("EXITING SIMULATION") == 4
    assert "--time-strategy best_effort" in log and "--time-strategy fixed_step" in log
    # logs and whatever the simulation writes in its working folder go to MORSE_TEST_LOGS, not beside the test
    assert [p.name for p in pose_test.parent.iterdir()] == ["pose_testing.py"]


def test_a_wrong_assertion_fails_the_file(pose_test, tmp_path):
    done = run_python([pose_test.name], pose_test.parent, PIDS_FILE=str(tmp_path / "pids"),
                      MORSE_TEST_LOGS=str(tmp_path / "logs"), EXPECTED_X="5.0")
    out = done.stdout + done.stderr
    assert done.returncode == 1, out
    assert "FAILED (failures=2)" in out and "AssertionError" in out
    assert all(gone(pid) for pid in pids_of(tmp_path / "pids"))


def test_pytest_runs_a_morse_test_file(pose_test, tmp_path):
    """Under pytest (no main()), each test runs once, in the scene's own time strategy."""
    done = run_python(["-m", "pytest", "-q", "-p", "no:cacheprovider", pose_test.name], pose_test.parent,
                      PIDS_FILE=str(tmp_path / "pids"), MORSE_TEST_LOGS=str(tmp_path / "logs"))
    assert done.returncode == 0, done.stdout + done.stderr
    assert "2 passed" in done.stdout
    assert all(gone(pid) for pid in pids_of(tmp_path / "pids"))


def test_builder_errors_name_the_test_file_line(tmp_path):
    path = write(tmp_path, "broken_testing.py", BROKEN_TEST)
    done = run_python([path.name], tmp_path, MORSE_TEST_LOGS=str(tmp_path / "logs"))
    out = done.stdout + done.stderr
    assert done.returncode == 1, out
    assert "FAILED (errors=2)" in out, out
    # a scene that does not build: the test errs with the builder's located message
    assert re.search(r"ERROR: test_never_reached .*\n(.*\n)*.*MorseTestingError: the scene of BrokenSceneTest does "
                     rf"not build: {re.escape(str(path))}:8:\d+: NameError: name 'NoSuchSensor'", out), out
    # MorseBuilderFailureTestCase: a refused scene passes, an accepted one is an error
    assert re.search(r"^test_refused \(.*\) \.\.\. .*ok$", out, re.M | re.S), out
    assert "ERROR: test_accepted" in out and "should have been refused" in out
    assert "invalid name 'a.b'" in (tmp_path / "logs" / "RefusedSceneTest.log").read_text()


def test_morse_builder_imports_in_plain_python(tmp_path):
    """No morsec command around: the `morse` package itself answers MORSE's builder imports."""
    script = write(tmp_path, "names.py", """
        from morse.builder import *
        from morse.builder.sensors import Pose as P
        from morse.builder.robots import ATRV as A
        from morse.builder.actuators import Light
        import morse.builder.morsebuilder, morsec.builder
        assert P is Pose is morsec.builder.Pose and A is ATRV and Environment is morsec.builder.Environment
        assert TimeStrategies.BestEffort != TimeStrategies.FixedSimulationStep
        assert math.pi > 3  # MORSE's star import handed over `math`; MORSE's test files use it unimported
        try:
            from morse.builder.robots import NoSuchRobot  # not in the catalogue: an ImportError, not a module
        except ImportError as err:
            assert "NoSuchRobot" in str(err)
        else:
            raise AssertionError(NoSuchRobot)
        from morse.testing.testing import MorseTestCase, main, testlogger, MorseMoveTestCase
        import unittest
        assert issubclass(MorseTestCase, unittest.TestCase)
        print("names ok")
    """)
    done = run_python([script.name], tmp_path)
    assert done.returncode == 0 and "names ok" in done.stdout, done.stdout + done.stderr


def test_importing_morse_testing_fixes_pymorse():
    import pymorse.pymorse

    import morse.testing.testing  # noqa: F401
    assert getattr(pymorse.pymorse.Morse.get_publisher_streams, "_morsec_patched", False)


def test_a_test_file_is_also_the_builder_script_of_its_scene(pose_test, tmp_path):
    """`morsec build my_test.py`: main() records the first case's setUpEnv(), as MORSE's `morse run` did."""
    done = run_python(["-m", "morsec", "build", pose_test.name, "-o", str(tmp_path / "build")], pose_test.parent)
    assert done.returncode == 0, done.stdout + done.stderr
    assert '"robot.pose"' in (tmp_path / "build" / "manifest.json").read_text()


# ------------------------------------------------------------------ morsec.app.process, which MorseTestCase uses

def two_rovers():
    from morsec.builder import ATRV, Environment, Pose
    robot = ATRV()
    pose = Pose()
    pose.add_stream("socket")
    robot.append(pose)
    env = Environment("empty")
    env.add_service("socket")
    rover = ATRV()  # noqa: F841 (created after the Environment: MORSE's default name, ATRV)


def no_environment():
    from morsec.builder import ATRV
    robot = ATRV()  # noqa: F841
    rover = ATRV()  # noqa: F841 (the last object: named after its variable when the function returns)


def test_record_call_names_objects_after_the_function_locals():
    from morsec.app.process import record_call
    recording = record_call(no_environment)
    assert [robot["name"] for robot in recording.data["robots"]] == ["robot", "rover"]


def test_an_object_created_after_the_environment_keeps_morse_default_name():
    """MORSE names objects after the script's variables when the Environment is constructed: one created
    later keeps its .blend object's name (search_and_rescue_testing's `Victim`), with a warning."""
    from morsec.app.process import record_call
    recording = record_call(two_rovers)
    assert [robot["name"] for robot in recording.data["robots"]] == ["robot", "ATRV"]
    warning, = [w for w in recording.records if "after Environment" in w.message]
    assert warning.line == two_rovers.__code__.co_firstlineno + 8
    assert "'ATRV'" in warning.message


def test_record_call_locates_an_error_in_the_function():
    from morsec.app.process import record_call
    from morsec.errors import SceneError

    def broken():
        from morsec.builder import ATRV
        ATRV().append(NoSuchSensor())  # noqa: F821

    with pytest.raises(SceneError, match="NoSuchSensor") as err:
        record_call(broken)
    assert (err.value.file, err.value.line) == (__file__, broken.__code__.co_firstlineno + 2)


def test_simulation_process_starts_and_stops(tmp_path):
    from morsec.app.process import SimulationProcess, build_call
    build = build_call(two_rovers, tmp_path / "build")
    sim = SimulationProcess(build, tmp_path / "sim.log", "fixed_step", ("--service-port", "0", "--port-base", "0"))
    sim.start()
    assert sim.running() and sim.ready.is_set()
    assert sim.stop() == 0 and not sim.running() and gone(sim.pid)
    assert sim.exited_by_itself is None and sim.stop() == 0  # stopped once, by us
    log = (tmp_path / "sim.log").read_text()
    assert "--time-strategy fixed_step" in log and "SCENE INITIALIZED" in log and "EXITING SIMULATION" in log


def test_a_simulation_that_does_not_start_says_why(tmp_path):
    from morsec.app.process import SimulationDidNotStart, SimulationProcess
    build = tmp_path / "build"
    build.mkdir()
    (build / "manifest.json").write_text("{}")
    sim = SimulationProcess(build, tmp_path / "sim.log")
    with pytest.raises(SimulationDidNotStart, match=r"exited with status 1 before SCENE INITIALIZED: error: .*not a usable build folder.*; see .*sim\.log"):
        sim.start()
    assert not sim.running()
