"""MORSE's test framework on morsec: `from morse.testing.testing import MorseTestCase, main`.

    from morse.testing.testing import MorseTestCase
    from morse.builder import *
    from pymorse import Morse

    class PoseTest(MorseTestCase):
        def setUpEnv(self):                  # builder calls: the scene every test of the case runs in
            robot = ATRV()
            pose = Pose(); pose.add_stream('socket'); robot.append(pose)
            env = Environment('empty'); env.add_service('socket')

        def test_read_pose(self):
            with Morse() as morse:
                self.assertAlmostEqual(morse.robot.pose.get()['x'], 0.0, 2)

    if __name__ == "__main__":
        from morse.testing.testing import main
        main(PoseTest)                       # every test once per time strategy

Each test runs on a simulation of its own, as in MORSE: `setUp` records the case's `setUpEnv()` into a
build folder (once per case and process: morsec's builder front end, in this process), starts
`morsec run BUILD --time-strategy S` as a child process and waits for SCENE INITIALIZED; `tearDown` stops it
(SIGINT, SIGKILL after a timeout). The simulation's output goes to `<logs>/<TestCase>.log`, where `<logs>` is
`$MORSE_TEST_LOGS`, else `<temp dir>/morse-testing/<test file name>-<pid>` (printed when a simulation fails).

`main(*cases, time_modes=[...])` runs every test of the cases once per time strategy (BestEffort, then
FixedSimulationStep, by default) and exits with unittest's status. Run by pytest instead, a test uses the time
strategy of its scene. Under `morsec build/run my_test.py`, `main()` records the first case's `setUpEnv()`:
the test file is also the builder script of its scene.

Importing this module fixes pymorse 1.4's `Morse.close()` on Python 3 (morsec.pymorse_compat), so that tests
are judged on the simulator, not on that client bug.
"""

from __future__ import annotations

import contextlib
import inspect
import logging
import os
import sys
import tempfile
import types
import unittest
from pathlib import Path

from morse.builder import TimeStrategies
from morse.testing.exceptions import MorseTestingError
from morsec.app.process import SimulationDidNotStart, SimulationProcess, build_call
from morsec.errors import MorsecError
from morsec.frontends.builder import builder_attribute, builder_names
from morsec.frontends.builder import session as _builder_session

testlogger = logging.getLogger("morsetesting.general")

try:
    from morsec.pymorse_compat import patch_pymorse
    patch_pymorse()
except ImportError:  # pymorse is not installed: tests that import it say so themselves
    pass

BLENDER_INITIALIZATION_TIMEOUT = 60  # seconds from `morsec run` to SCENE INITIALIZED (MORSE's name)

_MODES = {
    TimeStrategies.BestEffort: ("best_effort", "Best Effort"),
    TimeStrategies.FixedSimulationStep: ("fixed_step", "Fixed Simulation Step"),
}

CURRENT_TIME_MODE = None  # set by main() through MorseSwitchTimeMode; None: the scene's own strategy


def _strategy(mode) -> str | None:
    if mode is None:
        return None
    if mode in _MODES:
        return _MODES[mode][0]
    raise MorseTestingError(f"unknown time mode {mode!r}: use TimeStrategies.BestEffort or "
                            "TimeStrategies.FixedSimulationStep")


def human_repr(mode) -> str:
    return _MODES[mode][1] if mode in _MODES else "the scene's time strategy"


def logs_folder(case: type) -> Path:
    """Where the logs and build folders of a test case go: $MORSE_TEST_LOGS, else a folder in the temp dir
    named after the test file and this process (never next to the test file; two runs of the same file at
    once do not share their builds)."""
    explicit = os.environ.get("MORSE_TEST_LOGS")
    if explicit:
        return Path(explicit)
    source = inspect.getsourcefile(case) or getattr(sys.modules.get(case.__module__), "__file__", None) or "tests"
    return Path(tempfile.gettempdir()) / "morse-testing" / f"{Path(source).stem}-{os.getpid()}"


def with_builder_names(method):
    """`setUpEnv` as MORSE ran it: MORSE copied its source into a builder script that began with `from
    morse.builder import *`, so its builder calls need no import in the test file (robots/pr2/tuck_arms_ros.py
    has none). Here: the same function, seeing the builder's names over its module's."""
    func = getattr(method, "__func__", None)
    if func is None:
        return method
    scope = dict(func.__globals__)
    for name in builder_names():
        try:
            scope[name] = builder_attribute("morse.builder", name)
        except AttributeError:
            continue
    clone = types.FunctionType(func.__code__, scope, func.__name__, func.__defaults__, func.__closure__)
    clone.__kwdefaults__ = func.__kwdefaults__
    clone.__qualname__ = func.__qualname__
    clone.__module__ = func.__module__
    return types.MethodType(clone, method.__self__)


class MorseTestRunner(unittest.TextTestRunner):
    """unittest's text runner, one line per test (MORSE's conformance runner counts them), with MORSE's
    `morsetesting` log lines on stderr."""

    _logging_ready = False

    def __init__(self, *args, verbosity: int = 2, **kwargs):
        super().__init__(*args, verbosity=verbosity, **kwargs)

    @classmethod
    def setup_logging(cls) -> None:
        if cls._logging_ready:
            return
        logger = logging.getLogger("morsetesting")
        logger.setLevel(logging.DEBUG)
        handler = logging.StreamHandler()
        handler.setFormatter(logging.Formatter("[%(asctime)s (%(levelname)s)]   %(message)s"))
        logger.addHandler(handler)
        cls._logging_ready = True

    def run(self, test):
        self.setup_logging()
        return super().run(test)


class MorseSwitchTimeMode(unittest.TestCase):
    """Between two passes of main()'s tests: the next time strategy (it counts as a test, as in MORSE)."""

    def __init__(self, mode, methodName: str = "test_switch"):
        super().__init__(methodName)
        self.mode = mode

    def test_switch(self):
        global CURRENT_TIME_MODE
        CURRENT_TIME_MODE = self.mode


class MorseTestCase(unittest.TestCase):
    """A test case run against a simulation of the scene `setUpEnv()` describes, started anew for each test."""

    # per case (class): the build folder, or the error that prevented it; logs truncated once per process
    _builds: dict[type, Path | str] = {}
    _fresh_logs: set[Path] = set()

    def setUpEnv(self):
        """Overload this: the scene, with builder calls (`from morse.builder import *` at the top of the file)."""

    def setUpMw(self):
        """Overload this to prepare things before the simulation starts."""

    def tearDownMw(self):
        """Overload this to clean up what setUpMw prepared."""

    # ---- unittest

    def setUp(self):
        testlogger.info(f"Starting test {self.id()} in {human_repr(CURRENT_TIME_MODE)}")
        self.morse_initialized = False
        self.pid = None
        self.setUpMw()
        self.startmorse(self)

    def tearDown(self):
        self.stopmorse()
        self.tearDownMw()
        sim = getattr(self, "_simulation", None)
        if sim is not None and sim.exited_by_itself not in (None, 0):
            raise MorseTestingError(f"the simulation ended during the test with status {sim.exited_by_itself}"
                                    f"{sim.last_error()}; see {self.logfile_name}")

    def run(self, result=None):
        try:
            return super().run(result)
        finally:  # whatever happened (KeyboardInterrupt included), no simulation outlives its test
            self.stopmorse()

    # ---- the simulation

    @property
    def logfile_name(self) -> Path:
        return logs_folder(type(self)) / f"{type(self).__name__}.log"

    def _log(self, mode: str = "a"):
        path = self.logfile_name
        path.parent.mkdir(parents=True, exist_ok=True)
        if path not in MorseTestCase._fresh_logs:
            MorseTestCase._fresh_logs.add(path)
            mode = "w"
        return open(path, mode, encoding="utf-8")

    def build_scene(self) -> Path:
        """The build folder of this case's scene: setUpEnv() recorded and compiled once per process. A builder
        error (located in the test file) is logged and raised as MorseTestingError, for every test."""
        case = type(self)
        if case not in MorseTestCase._builds:
            out = logs_folder(case) / "build" / case.__name__
            with self._log() as log:
                log.write(f"== the scene of {case.__name__}: {case.__name__}.setUpEnv() ==\n")
                try:
                    with contextlib.redirect_stdout(log):
                        MorseTestCase._builds[case] = build_call(with_builder_names(self.setUpEnv), out,
                                                                 report=log)
                    log.write(f"built {out}\n")
                except MorsecError as err:
                    log.write(f"error: {err}\n")
                    MorseTestCase._builds[case] = str(err)
        built = MorseTestCase._builds[case]
        if isinstance(built, str):
            raise MorseTestingError(f"the scene of {case.__name__} does not build: {built}")
        return built

    def startmorse(self, test_case=None):
        """Build the scene (once), start `morsec run` on it, wait for SCENE INITIALIZED."""
        try:
            build = self.build_scene()
        except MorseTestingError as err:
            testlogger.error(f"{err} (log: {self.logfile_name})")
            raise
        with self._log() as log:
            log.write(f"== {self.id()} in {human_repr(CURRENT_TIME_MODE)} ==\n")
        self._simulation = SimulationProcess(build, self.logfile_name, _strategy(CURRENT_TIME_MODE))
        testlogger.info(f"Waiting for MORSE to initialize... (timeout: {BLENDER_INITIALIZATION_TIMEOUT} sec)")
        try:
            self._simulation.start(BLENDER_INITIALIZATION_TIMEOUT)
        except SimulationDidNotStart as err:
            testlogger.error("Error during MORSE initialization! Check the log file.")
            raise MorseTestingError(f"MORSE did not start successfully: {err}") from None
        self.morse_initialized = True
        self.pid = self._simulation.pid
        testlogger.info(f"MORSE successfully initialized with PID {self.pid}")

    def stopmorse(self):
        """Stop the simulation: SIGINT, then SIGKILL if it does not end. Harmless when it is not running."""
        sim = getattr(self, "_simulation", None)
        if sim is None or sim.process is None or sim.stopped:
            return
        sim.stop()
        testlogger.info("MORSE stopped")


class MorseMoveTestCase(MorseTestCase):
    """A case checking a moving robot by its pose. It assumes a robot `robot` with a pose sensor `robot.pose`
    and, for assertAlmostEqualPositionThenFix, the actuators `robot.motion` and `robot.teleport`."""

    def assertAlmostEqualPosition(self, morse, tested_pos, precision):
        """The pose (x, y, z, yaw, pitch, roll) is `tested_pos`, within `precision`."""
        pose = morse.robot.pose.get()
        for key, expected in zip(("x", "y", "z", "yaw", "pitch", "roll"), tested_pos):
            self.assertAlmostEqual(pose[key], expected, delta=precision)

    def assertAlmostEqualPositionThenFix(self, morse, tested_pos, precision):
        """As assertAlmostEqualPosition, then teleport the robot exactly there (errors do not add up)."""
        self.assertAlmostEqualPosition(morse, tested_pos, precision)
        morse.deactivate("robot.motion")
        morse.activate("robot.teleport")
        x, y, z, yaw, pitch, roll = tested_pos
        morse.robot.teleport.publish({"x": x, "y": y, "z": z + 0.01, "yaw": yaw, "pitch": pitch, "roll": roll})
        morse.sleep(0.1)
        morse.deactivate("robot.teleport")
        morse.activate("robot.motion")
        morse.sleep(0.1)


class MorseBuilderFailureTestCase(MorseTestCase):
    """A case whose `setUpEnv()` is a wrong builder script: its tests pass only if the scene is refused (the
    simulation is never started); a scene that builds is an error of every test."""

    def startmorse(self, test_case=None):
        testlogger.info("Waiting for MORSE to parse the scene...")
        try:
            self.build_scene()
        except MorseTestingError as err:
            testlogger.info(f"MORSE initialization error: {err}")
            self.morse_initialized = True
            return
        raise MorseTestingError(f"the scene of {type(self).__name__} built, but its builder script should have "
                                f"been refused; see {self.logfile_name}")


def main(*test_cases, time_modes=None):
    """Run every test of `test_cases` once per time mode (default: BestEffort, then FixedSimulationStep);
    exit with unittest's status. Inside `morsec build/run this_file.py`: record the first case's scene."""
    if time_modes is None:
        time_modes = [TimeStrategies.BestEffort, TimeStrategies.FixedSimulationStep]
    if _builder_session.recording_now():
        if test_cases:
            test_cases[0]().setUpEnv()
        return
    for mode in time_modes:
        _strategy(mode)  # an unknown mode fails before any simulation starts
    loader = unittest.TestLoader()
    suite = unittest.TestSuite()
    for mode in time_modes:
        suite.addTest(MorseSwitchTimeMode(mode))
        for case in test_cases:
            suite.addTests(loader.loadTestsFromTestCase(case))
    result = MorseTestRunner().run(suite)
    sys.exit(not result.wasSuccessful())
