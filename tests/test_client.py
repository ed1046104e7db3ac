"""morsec.client, the MORSE client with pymorse's API, against real `morsec run` subprocesses.

Every part of the API is checked on what the simulation does: a pose that changes after a publish, a
service's result, MORSE's own failure messages, preemption by cancel and by a newer request, close()
that returns at once and leaves no thread, a process that exits. The README's client snippet runs as
printed — in a network namespace of its own (`unshare -n`) against `morsec run scenes/tutorial.yaml` on
the default ports, and on any machine with only the port substituted — and the client runs under every
other Python 3.12+ found here (pyenv, uv or PATH), where pymorse 1.4 cannot even be imported.
"""

from __future__ import annotations

import ast
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest
from runtime_helpers import (
    MORSEC,
    READY,
    Morsec,
    free_port,
    pose_sensor,
    robot,
    scene,
    scene_file,
    start_all,
    wait_until,
)

from morsec.client import (
    Morse,
    MorseConnectionError,
    MorseFuture,
    MorseServerError,
    MorseServiceError,
    MorseServiceFailed,
    MorseServicePreempted,
    MorseTimeoutError,
    MorseWrongArguments,
)

REPO = Path(__file__).resolve().parents[1]
CLIENT = REPO / "morsec" / "client"
UNKNOWN_SERVICE = "The request 'fly' of component 'robot.motion' has not been registered in Socket service manager"
ROVER_Y = 8.0


def client_scene() -> dict:
    arm = pose_sensor("arm", translate=[0.3, 0.0, 0.4], components=[pose_sensor("tip", translate=[0.1, 0.0, 0.0])])
    main = robot("robot", pose_sensor(), {"name": "motion", "type": "motion_vw", "streams": ["socket"],
                                          "services": ["socket"]}, arm)
    rover = robot("rover", pose_sensor(), {"name": "wp", "type": "waypoint", "services": ["socket"]},
                  translate=[0.0, ROVER_Y, 0.0])
    return scene(main, robot("x", pose_sensor(), translate=[0.0, 4.0, 0.0]),
                 robot("x_001", pose_sensor(), translate=[0.0, -4.0, 0.0]), rover, strategy="best_effort")


@pytest.fixture(scope="module")
def servers(tmp_path_factory):
    """The simulation most tests share, and one for test_quit to end; started together."""
    tmp = tmp_path_factory.mktemp("client")
    shared = Morsec(scene_file(tmp, client_scene()), tmp)
    tmp_quit = tmp_path_factory.mktemp("client-quit")
    to_quit = Morsec(scene_file(tmp_quit, scene(strategy="best_effort")), tmp_quit)
    start_all(shared, to_quit)
    try:
        yield shared, to_quit
    finally:
        shared.stop()
        to_quit.stop()


@pytest.fixture
def server(servers):
    """The shared simulation with its robots stopped and back at their initial poses."""
    shared = servers[0]
    assert shared.alive(), shared.output()
    with shared.client() as client:
        client.ok("robot.motion", "stop")
        client.ok("simulation", "activate", "robot.pose")
        client.ok("simulation", "reset_objects")
    return shared


@pytest.fixture
def sim(server):
    morse = Morse("localhost", server.service_port)
    try:
        yield morse
    finally:
        morse.close(cancel_async_services=True)
        assert morse.threads == []


def client_threads() -> list[threading.Thread]:
    return [t for t in threading.enumerate() if t.name.startswith("morsec-client")]


def run_python(code: str, *, python: str = sys.executable, timeout: float = 120.0,
               args: tuple[str, ...] = (), cwd: Path | None = None) -> subprocess.CompletedProcess:
    """`code` in a fresh interpreter with this worktree's morsec on its path, warnings on (-X dev)."""
    env = dict(os.environ, PYTHONPATH=str(REPO), PYTHONDONTWRITEBYTECODE="1")
    return subprocess.run([python, "-X", "dev", "-c", textwrap.dedent(code), *args], capture_output=True,
                          text=True, timeout=timeout, env=env, cwd=cwd)


# ------------------------------------------------------------------------------------------ the module
def test_the_client_imports_only_the_standard_library():
    """A network client: no asyncore/asynchat, nothing of morsec's runtime or compiler, no numpy/MuJoCo,
    and it does not import (nor impersonate) pymorse."""
    stdlib = sys.stdlib_module_names
    for path in sorted(CLIENT.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and not node.level:
                names = [node.module]
            for name in names:
                top = name.split(".")[0]
                assert top in stdlib or name == "morsec.client", f"{path.name} imports {name}"
                assert top not in ("asyncore", "asynchat"), f"{path.name} imports {name}"
    result = run_python("""
        import sys, morsec.client
        print(sorted(m for m in sys.modules if m.split(".")[0] in
              ("asyncore", "asynchat", "pymorse", "numpy", "mujoco", "pydantic", "yaml", "morsec")))
        """)
    assert result.returncode == 0, result.stderr
    assert eval(result.stdout) == ["morsec", "morsec.client", "morsec.client.morse", "morsec.client.transport"]


def test_real_pymorse_is_left_alone():
    """morsec.client never registers itself as `pymorse`: pymorse 1.4 (which other tests use) imports
    as itself, after morsec.client too."""
    result = run_python("""
        import morsec.client, pymorse, pymorse.pymorse
        print(pymorse.__file__); print(pymorse.Morse is pymorse.pymorse.Morse)
        """)
    assert result.returncode == 0, result.stderr
    path, same = result.stdout.split()
    assert "site-packages" in path and Path(path).parent.name == "pymorse" and same == "True"


def test_the_exceptions():
    assert issubclass(MorseServiceFailed, MorseServiceError) and issubclass(MorseServiceError, MorseServerError)
    assert issubclass(MorseServicePreempted, MorseServiceError)
    assert issubclass(MorseWrongArguments, TypeError) and issubclass(MorseWrongArguments, MorseServiceFailed)
    assert issubclass(MorseConnectionError, ConnectionError) and issubclass(MorseTimeoutError, TimeoutError)
    assert str(MorseServiceFailed("as MORSE said")) == "as MORSE said"


# ------------------------------------------------------------------------------------------ discovery
def test_discovery(sim, server):
    assert sim.robots == ["robot", "x", "x_001", "rover"]
    assert sim.xs == [sim.x, sim.x_001] and sim.xs[0] is sim.x
    assert sim["robot"] is sim.robot and dict.__getitem__(sim.robot, "pose") is sim.robot.pose
    assert sim.robot.pose.fqn == "robot.pose" and sim.robot.pose.name == "pose"
    assert sim.robot.arm.tip.fqn == "robot.arm.tip"  # a sub-component, reached by its name path
    assert sim.x_001.pose.fqn == "x_001.pose"
    assert sorted(sim.robot) == ["arm", "motion", "pose"]
    assert sorted(sim.streams()) == sorted(server.streams)
    for fqn, (_, port) in server.streams.items():
        assert sim.get_stream_port(fqn) == port
    motion = sim.robot.motion
    assert callable(motion.set_speed) and callable(motion.stop) and callable(sim.rover.wp.goto)
    assert hasattr(motion, "publish") and not hasattr(motion, "get") and not hasattr(motion, "subscribe")
    assert hasattr(sim.robot.pose, "get") and not hasattr(sim.robot.pose, "publish")
    assert not hasattr(sim.rover.wp, "publish")  # services only: no stream
    with pytest.raises(AttributeError, match="an actuator: use publish"):
        motion.get  # noqa: B018
    with pytest.raises(AttributeError, match="no service or sub-component 'fly'"):
        motion.fly  # noqa: B018
    assert "set_speed" in dir(motion) and "get" not in dir(motion) and "tip" in dir(sim.robot.arm)


def test_loop_robots_named_robot_replace_the_name_list(tmp_path):
    """pymorse's quirk, kept: robots `robot`, `robot_001` make `sim.robots` the list of those robots."""
    scene_path = scene_file(tmp_path, scene(robot("robot", pose_sensor()),
                                            robot("robot_001", pose_sensor(), translate=[0.0, 3.0, 0.0])))
    with Morsec(scene_path, tmp_path) as server, Morse("localhost", server.service_port) as sim:
        assert sim.robots == [sim.robot, sim.robot_001]
        assert sim.robots[1].pose.get(timeout=10)["y"] == pytest.approx(3.0, abs=0.05)


def test_connection_refused():
    start = time.monotonic()
    with pytest.raises(ConnectionRefusedError):
        Morse("localhost", free_port())
    assert time.monotonic() - start < 5
    assert client_threads() == []


# ------------------------------------------------------------------------------------------ streams
def test_get_last_and_publish(sim):
    pose = sim.robot.pose
    first = pose.get(timeout=10)
    assert list(first) == ["timestamp", "x", "y", "z", "yaw", "pitch", "roll"]
    assert abs(first["x"]) < 0.05 and abs(first["y"]) < 0.05
    second = pose.get(timeout=10)
    assert second["timestamp"] > first["timestamp"]
    wait_until(lambda: len(pose.last(3)) == 3, message="three pose messages kept")
    three = pose.last(3)
    assert len(three) == 3 and three[0]["timestamp"] < three[1]["timestamp"] < three[2]["timestamp"]
    assert pose.last()["timestamp"] >= three[-1]["timestamp"] >= second["timestamp"]
    sim.robot.motion.publish({"v": 1.0, "w": 0.0})
    sim.sleep(1.0)
    moved = pose.get(timeout=10)
    assert moved["x"] > 0.7 and abs(moved["y"]) < 0.1  # it went forward, along x
    sim.robot.motion.publish({"v": 0.0, "w": 0.0})
    assert sim.robot.arm.tip.get(timeout=10)["z"] == pytest.approx(0.5, abs=0.05)
    assert sim.x.pose.get(timeout=10)["y"] == pytest.approx(4.0, abs=0.05)
    assert pose.get(timeout=0.0) is None  # a timeout: None, as pymorse
    with pytest.raises(TypeError, match="dict"):
        sim.robot.motion.publish([1.0, 0.0])
    with pytest.raises(ValueError):
        sim.robot.motion.publish({"v": float("nan")})  # refused here, not sent


def test_subscribe_and_unsubscribe(sim):
    received, threads, times = [], set(), []

    def callback(message):
        received.append(message)
        threads.add(threading.current_thread().name)
        if len(times) < 1:
            times.append(sim.time())  # a callback may call a service and wait for it

    pose = sim.robot.pose
    pose.subscribe(callback)
    wait_until(lambda: len(received) >= 5 and times, message="five pose messages through subscribe")
    pose.unsubscribe(callback)
    time.sleep(0.1)
    count = len(received)
    time.sleep(0.3)  # 18 messages at 60 Hz
    assert len(received) == count
    assert all(b["timestamp"] > a["timestamp"] for a, b in zip(received, received[1:]))
    assert threads == {"morsec-client-callbacks"} and times[0] > 1e9
    with pytest.raises(ValueError):
        pose.unsubscribe(callback)


def test_activate_and_deactivate(sim):
    pose = sim.robot.pose
    assert pose.get(timeout=10) is not None
    assert sim.deactivate("robot.pose") is None
    time.sleep(0.1)  # a message already on its way
    assert pose.get(timeout=0.5) is None
    assert sim.activate("robot.pose") is None
    assert pose.get(timeout=10) is not None
    sim.deactivate("robot.arm")
    try:
        assert sim.robot.arm.last() is None  # the first call connects; a silent sensor: nothing yet
        time.sleep(0.2)
        assert sim.robot.arm.last() is None and sim.robot.arm.last(5) == []
    finally:
        sim.activate("robot.arm")
    got = sim.robot.arm.get(timeout=10)
    assert got is not None and sim.robot.arm.last()["timestamp"] >= got["timestamp"]


def test_reset(sim):
    sim.robot.motion.set_speed(1.0, 0.0).result(timeout=10)
    sim.sleep(0.5)
    sim.robot.motion.stop().result(timeout=10)
    assert sim.robot.pose.get(timeout=10)["x"] > 0.3
    assert sim.reset() == "Objects restored to initial position"
    assert abs(sim.robot.pose.get(timeout=10)["x"]) < 0.05


# ------------------------------------------------------------------------------------------ services
def test_service_futures(sim):
    motion = sim.robot.motion
    future = motion.set_speed(1, 0)
    assert isinstance(future, MorseFuture)
    assert future.result(timeout=10) is None and future.done() and not future.running()
    assert not future.cancel()  # answered already: nothing to cancel
    sim.sleep(0.5)
    assert sim.robot.pose.get(timeout=10)["x"] > 0.3  # the service drove the robot
    assert motion.stop().result(timeout=10) is None
    properties = motion.get_properties()
    assert properties == {"ControlType": "Velocity"}  # comparing waits for the result, as in pymorse
    assert repr(properties) == "{'ControlType': 'Velocity'}"
    assert sim.rpc("simulation", "list_robots") == ["robot", "x", "x_001", "rover"]
    assert sim.rpc_t(10, "time", "mode") == "Best Effort"
    called = threading.Event()
    seen = []
    future = sim.rpc_async("time", "sleep", 0.2)
    future.add_done_callback(lambda f: (seen.append(f), called.set()))
    assert called.wait(10) and seen == [future] and future.result() is None


def test_a_failing_service_raises_morse_service_failed_with_morse_message(sim):
    with pytest.raises(MorseServiceFailed) as failed:
        sim.rpc("robot.motion", "fly")
    assert str(failed.value) == UNKNOWN_SERVICE
    assert (failed.value.component, failed.value.service) == ("robot.motion", "fly")
    future = sim.rpc_async("robot.motion", "fly")
    assert isinstance(future.exception(timeout=10), MorseServiceFailed) and future.done()
    with pytest.raises(MorseServiceFailed, match="^Stream unavailable for component robot.nothing$"):
        sim.get_stream_port("robot.nothing")
    with pytest.raises(TypeError, match="wrong # of parameters") as wrong:
        sim.robot.motion.set_speed(1.0).result(timeout=10)
    assert isinstance(wrong.value, MorseServiceFailed)
    with pytest.raises(MorseServiceFailed, match="parameters expected for service set_speed!") as expected:
        sim.robot.motion.set_speed().result(timeout=10)  # MORSE's words: not a TypeError, as in pymorse
    assert not isinstance(expected.value, TypeError)


def test_cancel_preempts_an_async_service(sim):
    long = sim.rpc_async("time", "sleep", 1000.0)
    short = sim.rpc_async("time", "sleep", 0.3)
    time.sleep(0.2)
    assert not long.done() and long.running()
    assert long.cancel()  # `<id> cancel`
    with pytest.raises(MorseServicePreempted):
        long.result(timeout=10)
    assert long.cancelled()
    assert short.result(timeout=10) is None  # the other sleep is not affected
    assert not short.cancelled()


def test_a_newer_request_preempts_an_interruptible_service(sim):
    wp = sim.rover.wp
    first = wp.goto(40.0, ROVER_Y, 0.0)
    time.sleep(0.2)
    second = wp.goto(-40.0, ROVER_Y, 0.0)
    with pytest.raises(MorseServicePreempted) as preempted:
        first.result(timeout=10)
    assert (preempted.value.component, preempted.value.service) == ("rover.wp", "goto")
    assert not second.done()
    assert wp.get_status() == "Transit"
    second.cancel()
    with pytest.raises(MorseServicePreempted):
        second.result(timeout=10)


def test_sleep_and_time_are_simulated(sim):
    t0, w0 = sim.time(), time.monotonic()
    assert t0 > 1e9  # epoch-based simulated time
    assert sim.sleep(0.5) is None
    t1, w1 = sim.time(), time.monotonic()
    assert t1 - t0 >= 0.5 - 1e-6
    assert w1 - w0 >= 0.4  # best_effort: a simulated half second takes about half a second


# ------------------------------------------------------------------------------------------ closing
def test_close_is_prompt_and_leaves_no_thread(server):
    sim = Morse("localhost", server.service_port)
    sim.robot.pose.subscribe(lambda message: None)  # starts the callback thread
    sim.robot.motion.publish({"v": 0.0, "w": 0.0})
    pending = sim.rpc_async("time", "sleep", 1000.0)
    wait_until(lambda: len(sim.threads) == 2, message="the I/O and callback threads running")
    time.sleep(0.1)  # the sleep request reached the simulation
    start = time.monotonic()
    sim.close(cancel_async_services=True)
    assert time.monotonic() - start < 3.0
    assert sim.threads == [] and client_threads() == [] and not sim.is_up()
    with pytest.raises((MorseServicePreempted, MorseConnectionError)):
        pending.result(timeout=0)
    sim.close()  # twice: nothing more
    with pytest.raises(MorseConnectionError):
        sim.rpc("time", "now")


def test_close_waits_for_running_requests(server):
    sim = Morse("localhost", server.service_port)
    running = sim.rpc_async("time", "sleep", 0.3)
    sim.close()  # as pymorse: the answers of the requests still running come first
    assert running.done() and running.result() is None
    assert sim.threads == []


def test_a_with_block_left_on_an_exception_cancels_requests(server):
    with pytest.raises(KeyError), Morse("localhost", server.service_port) as sim:
        running = sim.rpc_async("time", "sleep", 1000.0)
        time.sleep(0.1)
        raise KeyError("user code failed")
    assert isinstance(running.exception(timeout=0), (MorseServicePreempted, MorseConnectionError))
    assert sim.threads == []


def test_the_process_exits(server):
    """A script that ends its `with` block exits at once; one that forgets close() exits too (the
    client's threads are daemons), with nothing printed on stderr under -X dev."""
    for code in ("""
            import sys
            from morsec.client import Morse
            with Morse("localhost", int(sys.argv[1])) as sim:
                print(sim.robot.pose.get(timeout=10)["x"] < 0.05)
                sim.robot.motion.publish({"v": 0.0, "w": 0.0})
            """, """
            import sys
            from morsec.client import Morse
            sim = Morse("localhost", int(sys.argv[1]))
            sim.robot.pose.subscribe(lambda m: None)
            print(sim.robot.pose.get(timeout=10)["x"] < 0.05)
            sim.rpc_async("time", "sleep", 1000.0)   # never answered, never closed
            """):
        start = time.monotonic()
        result = run_python(code, args=(str(server.service_port),), timeout=60)
        assert result.returncode == 0 and result.stdout == "True\n", result.stdout + result.stderr
        assert time.monotonic() - start < 30


def test_quit(servers):
    server = servers[1]
    sim = Morse("localhost", server.service_port)
    other = Morse("localhost", server.service_port)
    pending = other.rpc_async("time", "sleep", 1000.0)
    assert sim.robot.pose.get(timeout=10) is not None
    sim.quit()  # `simulation quit`, then close()
    assert sim.threads == []
    assert server.wait(30) == 0
    assert "EXITING SIMULATION" in server.stdout
    with pytest.raises(MorseConnectionError, match="closed"):
        pending.result(timeout=10)  # the other client learns the simulation went away
    assert other.spin(timeout=10) and not other.is_up()
    other.close()
    assert client_threads() == []


# ------------------------------------------------------------------------------------------ pymorse scripts
def test_python_m_morsec_client_runs_a_pymorse_script(server, tmp_path):
    script = tmp_path / "old_client.py"
    script.write_text(textwrap.dedent("""\
        import sys
        import pymorse
        from pymorse import Morse, MorseServiceFailed
        with Morse("localhost", int(sys.argv[1])) as simu:
            print(simu.robot.pose.get(timeout=10)["x"] < 0.05)
            try:
                simu.rpc("robot.motion", "fly")
            except MorseServiceFailed as error:
                print(error)
        print(pymorse.__name__)
        """))
    env = dict(os.environ, PYTHONPATH=str(REPO))
    result = subprocess.run([sys.executable, "-m", "morsec.client", str(script), str(server.service_port)],
                            capture_output=True, text=True, timeout=60, env=env)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["True", UNKNOWN_SERVICE, "morsec.client"]
    usage = subprocess.run([sys.executable, "-m", "morsec.client"], capture_output=True, text=True, env=env)
    assert usage.returncode == 2 and "usage" in usage.stderr


# ------------------------------------------------------------------------------------------ the README
def readme_snippet() -> str:
    text = (REPO / "README.md").read_text(encoding="utf-8")
    blocks = [b for b in re.findall(r"```python\n(.*?)```", text, re.S) if "morsec.client import Morse" in b]
    assert len(blocks) == 1, "the README has one client snippet using morsec.client"
    assert blocks[0].count("Morse()") == 1
    return blocks[0]


def check_snippet_output(result: subprocess.CompletedProcess) -> None:
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stderr == ""
    assert float(result.stdout) == pytest.approx(2.0, abs=0.2)  # 1 m/s for 2 simulated seconds


def test_readme_snippet_with_the_port_substituted(server, tmp_path):
    """The snippet as printed, its `Morse()` pointed at this test's simulation."""
    snippet = readme_snippet().replace("Morse()", f'Morse("localhost", {server.service_port})')
    result = run_python(snippet, cwd=tmp_path)
    try:
        check_snippet_output(result)
    finally:
        with server.client() as client:
            client.ok("robot.motion", "stop")


def namespace_command() -> list[str] | None:
    """`unshare -n` (root) or `unshare -rn` (an unprivileged user namespace), if this machine allows one."""
    if not shutil.which("unshare") or not sys.platform.startswith("linux"):
        return None
    for command in (["unshare", "-n"], ["unshare", "-rn"]):
        if subprocess.run([*command, "true"], capture_output=True).returncode == 0:
            return command
    return None


NAMESPACE_RUNNER = '''
import fcntl, json, os, socket, struct, subprocess, sys, threading, time

# the namespace's loopback is down: bring it up (SIOCGIFFLAGS / SIOCSIFFLAGS, IFF_UP)
with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
    flags = struct.unpack("16sH22x", fcntl.ioctl(s, 0x8913, struct.pack("16sH22x", b"lo", 0)))[1]
    fcntl.ioctl(s, 0x8914, struct.pack("16sH22x", b"lo", flags | 1))

morsec, ready = sys.argv[1], sys.argv[2]
proc = subprocess.Popen([morsec, "run", "scenes/tutorial.yaml"], stdout=subprocess.PIPE,
                        stderr=subprocess.STDOUT, text=True)
watchdog = threading.Timer(150, lambda: (proc.kill(), os._exit(3)))
watchdog.daemon = True
watchdog.start()
log = []
for line in proc.stdout:
    log.append(line)
    if line.strip() == ready:
        break
threading.Thread(target=lambda: log.extend(proc.stdout), daemon=True).start()
try:
    snippet = subprocess.run([sys.executable, "snippet.py"], capture_output=True, text=True, timeout=120)
    out = {"returncode": snippet.returncode, "stdout": snippet.stdout, "stderr": snippet.stderr}
finally:
    proc.terminate()
    proc.wait(20)
print(json.dumps(dict(out, server="".join(log))))
'''


def test_readme_snippet_verbatim_in_its_own_network_namespace(tmp_path):
    """The snippet unchanged against `morsec run scenes/tutorial.yaml` unchanged, on the default ports
    (4000, 60000...): both run in a network namespace of their own, so that no other test or program
    holds those ports."""
    command = namespace_command()
    if command is None:
        pytest.skip("no network namespace here (unshare -n / -rn refused); see the port-substituted test")
    (tmp_path / "scenes").mkdir()
    shutil.copy(REPO / "scenes" / "tutorial.yaml", tmp_path / "scenes" / "tutorial.yaml")
    (tmp_path / "snippet.py").write_text(readme_snippet(), encoding="utf-8")
    (tmp_path / "runner.py").write_text(NAMESPACE_RUNNER, encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=str(REPO), PYTHONUNBUFFERED="1")
    done = subprocess.run([*command, sys.executable, "runner.py", str(MORSEC), READY], cwd=tmp_path,
                          capture_output=True, text=True, timeout=200, env=env)
    assert done.returncode == 0, done.stdout + done.stderr
    report = json.loads(done.stdout.splitlines()[-1])
    assert "127.0.0.1:4000" in report["server"] and "127.0.0.1:60000" in report["server"], report["server"]
    check_snippet_output(subprocess.CompletedProcess([], report["returncode"], report["stdout"], report["stderr"]))


# ------------------------------------------------------------------------------------------ other Pythons
def is_python(path: str, version: str) -> bool:
    """`path` runs and is that version (a pyenv shim may name a version it does not run)."""
    try:
        run = subprocess.run([path, "-c", "import sys; print('%d.%d' % sys.version_info[:2])"],
                             capture_output=True, text=True, timeout=30)
    except OSError:
        return False
    return run.returncode == 0 and run.stdout.strip() == version


def other_pythons() -> list:
    """pytest params (version, interpreter or None) for 3.12 and 3.13: from PATH, pyenv or uv."""
    found = []
    for version in ("3.12", "3.13"):
        candidates = [shutil.which(f"python{version}")]
        root = os.environ.get("PYENV_ROOT", os.path.expanduser("~/.pyenv"))
        candidates += sorted(glob.glob(f"{root}/versions/{version}*/bin/python{version}"))
        if shutil.which("uv"):
            uv = subprocess.run(["uv", "python", "find", "--no-project", version], capture_output=True, text=True)
            candidates.append(uv.stdout.strip() if uv.returncode == 0 else None)
        python = next((c for c in candidates if c and is_python(c, version)), None)
        found.append(pytest.param(version, python, id=f"python{version}"))
    return found


OTHER_PYTHON_CLIENT = '''
import sys, time
from morsec.client import Morse, MorseServiceFailed, MorseServicePreempted
with Morse("localhost", int(sys.argv[1])) as sim:
    before = sim.robot.pose.get(timeout=10)["x"]
    sim.robot.motion.publish({"v": 1.0, "w": 0.0})
    sim.sleep(0.5)
    after = sim.robot.pose.get(timeout=10)["x"]
    assert after > before + 0.25, (before, after)
    assert sim.robot.motion.stop().result(timeout=10) is None
    try:
        sim.rpc("robot.motion", "fly")
    except MorseServiceFailed as error:
        failed = str(error)
    long = sim.rpc_async("time", "sleep", 1000.0)
    time.sleep(0.1)
    long.cancel()
    try:
        long.result(timeout=10)
    except MorseServicePreempted:
        preempted = True
threads = sim.threads
print(sys.version_info[:2], failed, preempted, threads,
      sorted(m for m in ("asyncore", "asynchat") if m in sys.modules))
'''


@pytest.mark.parametrize("version,python", other_pythons())
def test_under_other_pythons(server, version, python):
    """pymorse 1.4 cannot import there (no asyncore from 3.12 on); this client works, warnings on."""
    if python is None:
        pytest.skip(f"no python{version} on this machine (PATH, pyenv, uv)")
    asyncore = run_python("import asyncore", python=python)
    assert asyncore.returncode != 0 and "asyncore" in asyncore.stderr
    result = run_python(OTHER_PYTHON_CLIENT, python=python, args=(str(server.service_port),))
    assert result.returncode == 0 and result.stderr == "", result.stdout + result.stderr
    major, minor = (int(n) for n in version.split("."))
    assert result.stdout == f"({major}, {minor}) {UNKNOWN_SERVICE} True [] []\n"
    snippet = readme_snippet().replace("Morse()", f'Morse("localhost", {server.service_port})')
    with server.client() as client:
        client.ok("simulation", "reset_objects")
    try:
        check_snippet_output(run_python(snippet, python=python))
    finally:
        with server.client() as client:
            client.ok("robot.motion", "stop")
