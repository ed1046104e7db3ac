"""Time strategies, lockstep, relative time, and how `morsec run` starts and ends (reference §5)."""

from __future__ import annotations

import contextlib
import json
import signal
import socket
import subprocess
import time
from pathlib import Path

import pytest
from runtime_helpers import (
    MORSEC,
    LineSocket,
    Morsec,
    build_folder,
    free_port,
    friction_loss,
    occupy,
    pose_sensor,
    robot,
    scene,
    scene_file,
    start_all,
    stop_all,
    wait_until,
)

from morsec.constants import SLEEP_HOLD_GRACE

DT = 1.0 / 60
LOST = friction_loss()


def refused(host: str, port: int) -> bool:
    try:
        socket.create_connection((host, port), timeout=5).close()
    except ConnectionRefusedError:
        return True
    return False


def fast_sim(tmp: Path) -> Morsec:
    return Morsec(scene_file(tmp, scene(strategy="best_effort"), "fast"), tmp, prebuild=False,  # builds, then runs
                  args=["--time-strategy", "fixed_step", "--duration", "30"])


def scaled_sim(tmp: Path) -> Morsec:
    return Morsec(scene_file(tmp, scene(strategy="best_effort"), "scaled"), tmp, args=["--time-scale", "2"])


def relative_sim(tmp: Path) -> Morsec:
    return Morsec(scene_file(tmp, scene(environment={"time": {"relative": True}}, strategy="best_effort"),
                             "relative"), tmp, host="127.0.0.2", args=["--bind", "127.0.0.2"])


def lockstep_sim(tmp: Path) -> Morsec:
    sync_port = free_port()
    sim = Morsec(scene_file(tmp, scene(strategy="fixed_step", environment={
        "stream_managers": {"socket": {"time_sync": True, "sync_port": sync_port}}}), "lockstep"), tmp)
    sim.expected_sync_port = sync_port
    return sim


@pytest.fixture
def launch(tmp_path):
    """`launch(fast_sim)`: that simulation, started for this test alone and ready; stopped when the test
    ends. No test shares a simulation: none depends on what another did to one (quit it, signalled it,
    changed its time scale) nor on the order the tests run in."""
    started = []

    def launch(make) -> Morsec:
        sim = make(tmp_path)
        started.append(sim)
        start_all(sim)
        return sim

    try:
        yield launch
    finally:
        stop_all(*started)


def test_fixed_step_runs_faster_than_real_time_and_duration_ends_it(launch):
    fast = launch(fast_sim)
    assert fast.wait(60) == 0, fast.output()
    wall = fast.seen_at["EXITING SIMULATION"] - fast.seen_at["SCENE INITIALIZED"]
    assert wall < 15.0, f"30 simulated seconds took {wall:.1f} s"  # at least twice real time, even on a busy host


def test_best_effort_follows_the_wall_clock_times_the_scale(launch):
    scaled = launch(scaled_sim)
    with scaled.client() as client:
        assert client.ok("time", "mode") == "Best Effort"
        w0 = time.monotonic()
        client.ok("time", "sleep", 2.0, timeout=20)
        at_two = time.monotonic() - w0
        assert client.ok("time", "set_time_scale", 1.0) is True
        w0 = time.monotonic()
        client.ok("time", "sleep", 2.0, timeout=20)
        at_one = time.monotonic() - w0
    assert 0.8 <= at_two <= 1.6, f"2 simulated s at scale 2 took {at_two:.2f} s"
    assert 1.8 <= at_one <= 2.8, f"2 simulated s at scale 1 took {at_one:.2f} s"


def test_quit_service_exits_0_and_closes_the_ports(launch):
    scaled = launch(scaled_sim)
    ports = [scaled.service_port] + [p for _, p in scaled.streams.values()]
    assert scaled.request("q simulation quit") == "q SUCCESS"
    assert scaled.wait(30) == 0, scaled.output()
    assert "EXITING SIMULATION" in scaled.stdout
    assert all(refused("127.0.0.1", p) for p in ports)


def test_relative_time_and_bind(launch):
    sim = launch(relative_sim)
    assert all("127.0.0.2:" in line for line in sim.stdout if line.startswith("  ") and "socket" in line)
    with sim.client() as client:
        now = client.ok("time", "now")
    assert 0 < now < 60  # from 0, not the Unix epoch
    with sim.stream("robot.pose") as pose:
        assert 0 < pose.json()["timestamp"] < 60
    assert refused("127.0.0.1", sim.service_port)  # listening on the --bind address only


def test_sigint_exits_0(launch):
    sim = launch(relative_sim)
    sim.signal(signal.SIGINT)
    assert sim.wait(30) == 0, sim.output()
    assert "EXITING SIMULATION" in sim.stdout
    assert not [line for line in sim.stderr if "Traceback" in line]


def test_lockstep(launch):
    sim = launch(lockstep_sim)
    assert sim.sync_port == sim.expected_sync_port
    with sim.client() as client:
        t = client.ok("time", "now")
        wait_until(lambda: client.ok("time", "now") > t, message="free running before a sync client")
        with LineSocket(sim.sync_port) as sync:
            time.sleep(0.3)  # accepted: the loop now waits for steps
            t0 = client.ok("time", "now")
            time.sleep(0.3)
            assert client.ok("time", "now") == t0, "time advanced without a step"
            for k in (5, 1, 3):
                sync.send("step\n" * k)  # k lines in one write: k frames
                target = t0 + k * DT
                wait_until(lambda target=target: client.ok("time", "now") >= target - 1e-9, timeout=10,
                           message=f"{k} steps")
                time.sleep(0.2)
                now = client.ok("time", "now")
                assert now == pytest.approx(target, abs=1e-5), (k, now - t0)  # epoch-based: ~2e-7 resolution
                t0 = now
            with sim.stream("robot.pose") as pose:  # sensors publish on steps only
                sync.send("\n\n")
                stamps = [pose.json()["timestamp"], pose.json()["timestamp"]]
                assert stamps[1] - stamps[0] == pytest.approx(DT, abs=1e-5)
                with pytest.raises(TimeoutError):
                    pose.line(timeout=0.3)
            t0 = client.ok("time", "now")
        wait_until(lambda: client.ok("time", "now") > t0 + 0.5, timeout=10, message="free running after disconnect")


# ------------------------------------------------------------------ MORSE's frame order, frame by frame
def frame_order_sim(tmp: Path) -> Morsec:
    """Lockstep (each line on the sync port: one frame): an ATRV driven by motion_vw, another by a waypoint
    actuator (an asynchronous service), each with a pose stream."""
    sync_port = free_port()
    walker = robot("walker", pose_sensor(), {"name": "waypoint", "type": "waypoint", "streams": ["socket"],
                                             "services": ["socket"]}, translate=[0.0, 5.0, 0.0])
    sim = Morsec(scene_file(tmp, scene(robot(), walker, strategy="fixed_step", environment={
        "stream_managers": {"socket": {"time_sync": True, "sync_port": sync_port}}}), "frame_order"), tmp)
    sim.expected_sync_port = sync_port
    return sim


def test_what_a_client_sends_after_a_frame_acts_from_the_frame_after_the_next(launch):
    """MORSE's frame order (docs/running.md#time), one frame at a time: what a client sends after a frame's
    messages and answers is taken with the end of the next frame. A message to an actuator moves the robot
    from the second frame on, a sleep of 3 frames ends 4 frames on, a component's asynchronous service starts
    with the next frame's end, and each round trip since the client's last command puts its next sleep a
    frame later."""
    sim = launch(frame_order_sim)
    with (sim.client() as client, LineSocket(sim.sync_port) as sync, sim.stream("robot.motion") as motion,
          sim.stream("robot.pose") as pose, sim.stream("walker.pose") as walker_pose):
        time.sleep(0.3)  # the sync client accepted: frames on its lines only

        def frame() -> tuple[float, float]:
            """One frame; the x of both robots after it."""
            sync.send("\n")
            return pose.json()["x"], walker_pose.json()["x"]

        def frames_until_answered(request_id: str, most: int = 12) -> int:
            for n in range(1, most + 1):
                frame()
                with contextlib.suppress(TimeoutError):
                    client.response(request_id, timeout=0.2)
                    return n
            raise AssertionError(f"{request_id} not answered within {most} frames")

        for _ in range(3):
            x0, _ = frame()
        motion.send('{"v": 1.0, "w": 0.0}\n')
        time.sleep(0.2)  # read by the loop, between two frames
        x1, _ = frame()
        assert x1 == pytest.approx(x0, abs=1e-9)  # the frame after: not yet
        x2, _ = frame()
        assert x2 > x1 + 0.01  # the frame after the next: moving
        motion.send('{"v": 0.0, "w": 0.0}\n')
        for _ in range(30):
            frame()

        sleep = client.send_request("time", "sleep", 3 * DT)
        time.sleep(0.2)
        assert frames_until_answered(sleep) == 4  # counted from the end of the next frame

        assert client.ok("robot.motion", "set_speed", 0.0, 0.0) is None  # a command, answered at once
        client.ok("time", "now")  # round trips after it, with no frame in between: MORSE read them a frame
        client.ok("time", "now")  # apart, and the sleep after them three frames after the command
        sleep = client.send_request("time", "sleep", 3 * DT)
        time.sleep(0.2)
        assert frames_until_answered(sleep) == 7

        _, w0 = frame()
        goto = client.send_request("walker.waypoint", "goto", 3.0, 5.0, 0.0, 0.1, 1.0)
        time.sleep(0.2)
        _, w1 = frame()  # the goto starts at this frame's end
        assert w1 == pytest.approx(w0, abs=1e-9)
        _, w2 = frame()
        assert w2 > w1 + 0.01
        client.send(f"{goto} cancel\n")
        assert client.response(goto)[1] == "PREEMPTED"


# ------------------------------------------------------------------ fixed_step: clients pacing with time sleep
def paced_sim(tmp: Path) -> Morsec:
    return Morsec(scene_file(tmp, scene(strategy="fixed_step"), "paced"), tmp)  # ATRV, pose, motion_vw


def pose_x(sim: Morsec) -> float:
    with sim.stream("robot.pose") as pose:
        return pose.json()["x"]


def test_fixed_step_commands_apply_where_the_sleep_ended(launch):
    """MORSE's vw_testing in fixed_step, at a hundred times real time: set_speed, sleep 2, stop drives 2 m,
    as in best_effort. The stop arrives a round trip after the sleep's answer; meanwhile the loop follows the
    wall clock (a frame per 1/60 s), so it lands at the first frame after the sleep's end."""
    sim = launch(paced_sim)
    with sim.client() as client, sim.stream("robot.motion") as motion:
        assert client.ok("time", "mode") == "Fixed Simulation Step"
        client.ok("time", "sleep", 0.5)  # landed; the loop now waits for this client's next sleep
        x0 = pose_x(sim)
        client.ok("time", "sleep", 0.1)
        client.ok("robot.motion", "set_speed", 1.0, 0.0)  # services
        client.ok("time", "sleep", 2.0)
        client.ok("robot.motion", "stop")
        x1 = pose_x(sim)
        assert x1 - x0 == pytest.approx(2.0 * (1.0 - LOST), abs=0.05), (x0, x1)
        client.ok("time", "sleep", 0.1)
        motion.send('{"v": -1.0, "w": 0.0}\n')  # the actuator's stream
        client.ok("time", "sleep", 2.0)
        motion.send('{"v": 0.0, "w": 0.0}\n')
        client.ok("time", "sleep", 0.1)
        x2 = pose_x(sim)
        assert x2 - x1 == pytest.approx(-2.0 * (1.0 - LOST), abs=0.05), (x1, x2)
        stats = client.ok("time", "statistics")
    assert stats["real_time_factor"] > 5, stats  # it did run fast
    assert stats["sleep_holds"] >= 6, stats


def sim_rate(probe, seconds: float) -> float:
    """Simulated seconds per wall-clock second over about `seconds` of wall time."""
    t0, w0 = probe.ok("time", "now"), time.monotonic()
    time.sleep(seconds)
    return (probe.ok("time", "now") - t0) / (time.monotonic() - w0)


def test_a_client_that_sleeps_then_goes_silent_slows_the_loop_no_longer_than_the_grace(launch):
    """After its sleep the loop follows the wall clock until the client's next sleep, for SLEEP_HOLD_GRACE
    at most: then as fast as it can again."""
    sim = launch(paced_sim)
    with sim.client() as probe:
        # fixed_step: far faster than real time, once the probe's first request is a grace behind
        wait_until(lambda: sim_rate(probe, 0.3) > 5, timeout=10, message="running free")
        with sim.client() as sleeper:
            end = probe.ok("time", "now") + 0.2
            sleeper.ok("time", "sleep", 0.2)  # then nothing
            w0 = time.monotonic()
            assert probe.ok("time", "now") == pytest.approx(end, abs=0.15)  # at the wall clock's pace
            assert sim_rate(probe, 0.3) < 1.5
            time.sleep(max(0.0, w0 + SLEEP_HOLD_GRACE + 0.2 - time.monotonic()))
            assert sim_rate(probe, 0.3) > 5
            stats = probe.ok("time", "statistics")
            assert (stats["sleep_holds"], stats["sleep_holds_overtime"]) == (1, 1)
            # a client that pipelined many sleeps slows the loop after its last one only
            sleeper.send("".join(f"p{i} time sleep [{0.05 * i}]\n" for i in range(1, 101)))
            t0, w0 = probe.ok("time", "now"), time.monotonic()
            assert [sleeper.line() for _ in range(100)][-1] == "p100 SUCCESS"
            wait_until(lambda: probe.ok("time", "now") > t0 + 10.0, timeout=20, message="10 simulated s")
            assert time.monotonic() - w0 < SLEEP_HOLD_GRACE + 5.0  # 10 simulated s, at most one grace of them paced
            assert probe.ok("time", "statistics")["sleep_holds"] == 2
        # a client that leaves as soon as its sleep ends slows nothing down
        with sim.client() as leaver:
            leaver.ok("time", "sleep", 0.1)
        assert sim_rate(probe, 0.3) > 5


def test_a_new_client_has_the_wall_clock_until_its_first_sleep(launch):
    """MORSE's battery test in fixed_step: `bat.get(); sleep(2); bat.get()` reads 2 s of discharge, not 2 s
    and the frames run between the read and the sleep: from a client's first request to its first sleep the
    loop follows the wall clock (SLEEP_HOLD_GRACE at most), as between two sleeps."""
    sim = launch(paced_sim)
    with sim.client() as observer:
        wait_until(lambda: sim_rate(observer, 0.3) > 5, timeout=10, message="running free")
        with sim.client() as newcomer:
            assert sim_rate(newcomer, 0.3) < 1.5  # its first request: the wall clock's pace
            t0 = newcomer.ok("time", "now")
            newcomer.ok("time", "sleep", 0.5)
            assert newcomer.ok("time", "now") - t0 == pytest.approx(0.5, abs=2 * DT)
        wait_until(lambda: sim_rate(observer, 0.3) > 5, timeout=10, message="free again once it left")


def test_new_actuator_stream_connections_are_waited_for_briefly(launch):
    """A new connection to an actuator stream: the loop waits for its first message (pymorse's lags behind
    the request that follows it), SLEEP_HOLD_WAIT at most; connecting again and again cannot stop it."""
    sim = launch(paced_sim)
    with sim.client() as probe:
        with sim.stream("robot.motion") as motion:
            t0 = probe.ok("time", "now")
            time.sleep(0.05)
            assert probe.ok("time", "now") - t0 < 0.1  # waiting for its first line (else 5 s or more)
            motion.send('{"v": 0.0, "w": 0.0}\n')
            wait_until(lambda: probe.ok("time", "now") > t0 + 2.0, timeout=5, message="going on after the line")
        opened = []
        try:
            t0, w0 = probe.ok("time", "now"), time.monotonic()
            while time.monotonic() - w0 < 2.0:  # a silent connection every 50 ms
                opened.append(sim.stream("robot.motion"))
                time.sleep(0.05)
            rate = (probe.ok("time", "now") - t0) / (time.monotonic() - w0)
        finally:
            for sock in opened:
                sock.close()
    assert rate > 5, f"{rate:.1f} simulated s per wall s"


def test_after_waiting_for_a_new_stream_frames_keep_the_wall_clocks_pace(launch):
    """MORSE's battery test in fixed_step: pymorse opens the teleport's stream, which stays silent, and then
    reads the battery with `get()`: the loop waits for the stream's first line (SLEEP_HOLD_WAIT) and that
    wait is not owed: the frame after the wait is followed by the next a frame's time later, not at once, so
    that a client's reply to the first frame's message (`get(); sleep(2)`) arrives before the next frame."""
    sim = launch(paced_sim)
    with sim.client() as client, sim.stream("robot.pose") as pose:
        client.ok("time", "now")  # its first request: the wall clock's pace until its first sleep
        pose.json()
        with sim.stream("robot.motion"):  # silent
            arrived = time.monotonic()
            while True:
                message = pose.json()
                arrived, gap = time.monotonic(), time.monotonic() - arrived
                if gap > 0.1:  # the first frame after the wait
                    break
            time.sleep(0.005)  # pymorse's reply takes a few milliseconds (its polling thread, its get())
            assert client.ok("time", "now") == pytest.approx(message["timestamp"], abs=1e-6)


def test_a_client_that_reads_a_stream_after_its_sleep_reads_the_next_frame(launch):
    """`sleep; pose.get()`: the stream needs frames; they come at the wall clock's pace, the first one right
    after the sleep's end, whether the client says something first or not."""
    sim = launch(paced_sim)
    with sim.client() as client, sim.stream("robot.pose") as pose:
        w0 = time.monotonic()
        for _ in range(20):
            client.ok("time", "sleep", 0.05)
            ended = client.ok("time", "now")
            while (stamp := pose.json()["timestamp"]) <= ended + 1e-6:
                pass  # older messages still on their way
            assert stamp == pytest.approx(ended + DT, abs=1e-5)
        w1 = time.monotonic()
        for _ in range(20):
            client.ok("time", "sleep", 0.05)
            pose.drain()
            pose.json()
        assert time.monotonic() - w1 < 20 * 3 * DT + 3.0  # no wait for the client: a frame or two each
        assert w1 - w0 < 20 * 3 * DT + 3.0
        stats = client.ok("time", "statistics")
    assert stats["sleep_holds"] == 40, stats


def drain_lines(sock: LineSocket) -> list:
    """The complete lines already on the socket (nothing is waited for)."""
    sock.sock.setblocking(False)
    try:
        while True:
            chunk = sock.sock.recv(65536)
            if not chunk:
                break
            sock.buffer += chunk
    except (BlockingIOError, InterruptedError):
        pass
    finally:
        sock.sock.setblocking(True)
        sock.sock.settimeout(sock.timeout)
    *lines, sock.buffer = sock.buffer.split(b"\n")
    return [json.loads(line) for line in lines if line.strip()]


@pytest.mark.parametrize("make", [paced_sim, scaled_sim], ids=["fixed_step", "best_effort"])
def test_a_frames_messages_leave_before_the_answer_to_a_sleep_that_ended_at_it(launch, make):
    """MORSE's accelerometer test: `publish(stop); sleep(0.01); last()` reads the deceleration. A sleep's
    answer leaves after the messages of the frame it ended at, so a client holding the answer holds them
    too (on the loopback a message is in the reader's buffer as soon as it is sent)."""
    sim = launch(make)
    with sim.client() as client, sim.stream("robot.pose") as pose:
        client.ok("time", "set_time_scale", 0.2)  # a frame every 1/12 s of wall time: none passes unseen below
        for _ in range(5):
            client.ok("time", "sleep", 0.05)
            last = drain_lines(pose)[-1]["timestamp"]  # what had arrived with the answer
            now = client.ok("time", "now")  # the frame the sleep ended at (the next one is 1/12 s away)
            assert last == pytest.approx(now, abs=1e-6), (last, now)


def real_time_sim(tmp: Path) -> Morsec:
    return Morsec(scene_file(tmp, scene(strategy="best_effort"), "real_time"), tmp)


def four_sensor_sim(tmp: Path) -> Morsec:
    """A robot with, in this order: a velocity sensor in Velocity mode, one in Position mode, two poses (a, b),
    and a motion actuator driving the robot, created last."""
    def velocity(name: str, mode: str) -> dict:
        return {"name": name, "type": "velocity", "streams": ["socket"], "properties": {"ComputationMode": mode}}
    motion = {"name": "motion", "type": "motion_vw", "streams": ["socket"]}
    robot_ = robot("robot", velocity("v", "Velocity"), velocity("v_pos", "Position"), pose_sensor("a"),
                   pose_sensor("b"), motion)
    return Morsec(scene_file(tmp, scene(robot_, strategy="best_effort"), "four_sensors"), tmp)


def test_a_frames_messages_leave_apart_in_morses_order(launch):
    """A reader polling its sockets as pymorse does (select on all of them, then each ready one read in the
    order it opened them) reads a frame's messages one at a time, in MORSE's order: `v` (Velocity mode,
    created before the actuator driving the robot: MORSE ran it after that actuator, sending its decision a
    frame before the others did) first, then the others, the one created last first (b before a, as MORSE's
    accelerometer test needs for `accel.get(); accel_pi.last()`, and v before v_pos as its attitude test does
    for `attitude_pos.get(); attitude.last()`). Sent together, the reader would read a before b."""
    import select
    sim = launch(four_sensor_sim)
    names = ("a", "b", "v", "v_pos")  # opened in this order
    with contextlib.ExitStack() as stack:
        socks = [stack.enter_context(sim.stream(f"robot.{name}")) for name in names]
        for sock in socks:
            sock.sock.setblocking(False)
        seen: dict[float, list[str]] = {}  # frame (timestamp) -> the streams, in the order their messages were read
        deadline = time.monotonic() + 2.0
        while time.monotonic() < deadline:
            ready, _, _ = select.select([s.sock for s in socks], [], [], 0.01)
            for sock, name in zip(socks, names):
                if sock.sock in ready:
                    sock.buffer += sock.sock.recv(65536)
                    while b"\n" in sock.buffer:
                        line, _, sock.buffer = sock.buffer.partition(b"\n")
                        seen.setdefault(json.loads(line)["timestamp"], []).append(name)
    frames = [order for order in list(seen.values())[1:-1] if len(order) == 4]  # whole frames, once all connected
    assert len(frames) > 60
    b_first = sum(order.index("b") < order.index("a") for order in frames)
    v_first = sum(order.index("v") < order.index("v_pos") for order in frames)
    # sent together, a would come first (b in a fifth of the frames at most); a reader starved of the CPU
    # for longer than the gap (a busy machine) reads some frames together
    assert b_first > 2 / 3 * len(frames), (b_first, len(frames), frames[:5])
    assert v_first > 2 / 3 * len(frames), (v_first, len(frames), frames[:5])


def test_the_frame_after_a_sleep_answer_that_waited_for_a_new_stream_client_comes_a_frame_later(launch):
    """The answer to a sleep that ends right after a client connected to a sensor stream waits for that
    client (READER_POLL); the wait is not taken out of the next frame's: it still comes a frame's time
    after the answer, so that a client calling `get()` once it has the answer gets it."""
    sim = launch(real_time_sim)
    with sim.client() as client, sim.stream("robot.pose") as frames:
        for k in range(8):
            frames.drain()
            sleep = client.send_request("time", "sleep", 0.01)  # ends at the end of the second frame from now
            frames.json()  # the first of them
            time.sleep(0.003 + k * 0.0008)  # then a new client of a sensor stream, less than READER_POLL before
            with sim.stream("robot.pose") as pose:  # the sleep's end
                client.response(sleep)
                answered = time.monotonic()
                pose.drain()  # the messages of the frame the sleep ended at
                pose.json()
                assert time.monotonic() - answered > 0.75 * DT, k


def test_fixed_step_a_sleep_after_a_stream_command_counts_from_it(launch):
    """`motion.publish(v=1); sleep(1)` from a loop running free at a hundred times real time: the loop
    follows the wall clock after the command and the sleep counts from the frame it arrived at, so the
    robot drives 1 m, not 1 m plus the frames between the two messages."""
    sim = launch(paced_sim)
    with sim.client() as client, sim.stream("robot.motion") as motion, sim.stream("robot.pose") as pose:
        motion.send('{"v": 0.0, "w": 0.0}\n')
        wait_until(lambda: sim_rate(client, 0.2) > 5, timeout=10, message="running free again")
        x0 = pose.json()["x"]
        motion.send('{"v": 1.0, "w": 0.0}\n')
        time.sleep(0.02)  # the sleep comes later than the command: a client thinking, or pymorse's threads
        client.ok("time", "sleep", 1.0)
        motion.send('{"v": 0.0, "w": 0.0}\n')
        client.ok("time", "sleep", 0.5)
        pose.drain()
        x1 = pose.json()["x"]
    assert x1 - x0 == pytest.approx(1.0 - LOST, abs=0.05), (x0, x1)


def test_fixed_step_a_sleep_does_not_count_from_another_clients_stream_command(launch):
    """A sleep right after a message to an actuator stream counts from it (above), but not the sleep of a
    client whose first request came after the message: pymorse opens its streams after its service
    connection, so the message was another client's (a session that had just ended)."""
    sim = launch(paced_sim)
    with sim.stream("robot.motion") as motion:
        motion.send('{"v": 0.0, "w": 0.0}\n')
        time.sleep(0.05)  # a few frames, at the wall clock's pace after a stream command
        with sim.client() as client:
            t0 = client.ok("time", "now")
            client.ok("time", "sleep", 0.5)
            assert client.ok("time", "now") - t0 >= 0.5 - 1e-6


def test_sigterm_exits_0(launch):
    sim = launch(lockstep_sim)
    sim.signal(signal.SIGTERM)
    assert sim.wait(30) == 0, sim.output()
    assert "EXITING SIMULATION" in sim.stdout
    assert not [line for line in sim.stderr if "Traceback" in line]


# --------------------------------------------------------------------------------------- failures
@pytest.fixture(scope="module")
def launched_failures(tmp_path_factory):
    """`morsec run` of things that cannot run, launched side by side: ({case: Popen}, held sockets, paths)."""
    tmp = tmp_path_factory.mktemp("failures")
    built = build_folder(scene_file(tmp, scene(), "good"), tmp / "good")
    garbage = tmp / "garbage"
    garbage.mkdir()
    (garbage / "manifest.json").write_text("not json")
    old = tmp / "old"
    old.mkdir()
    (old / "manifest.json").write_text("{}")
    (old / "middleware.json").write_text("{}")
    invalid = scene_file(tmp, scene(robot("robot", pose_sensor(translte=[0, 0, 0]))), "invalid")
    cases = {
        "ports busy": [str(MORSEC), "run", str(built), "--duration", "1"],
        "garbage build": [str(MORSEC), "run", str(garbage), "--duration", "1"],
        "old build": [str(MORSEC), "run", str(old), "--duration", "1"],
        "invalid scene": [str(MORSEC), "run", str(invalid), "--duration", "1"],
    }
    held = []
    for port in range(4000, 4011):  # every service port morsec would try
        with contextlib.suppress(OSError):
            held.append(occupy(port))
    procs = {case: subprocess.Popen(command, cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for case, command in cases.items()}
    try:
        yield procs, held, {"invalid scene": invalid}
    finally:
        for sock in held:
            sock.close()
        for proc in procs.values():
            if proc.poll() is None:
                proc.kill()
            proc.communicate()


@pytest.fixture(scope="module")
def failures(launched_failures):
    """{case: CompletedProcess} of the launched failures."""
    procs, held, paths = launched_failures
    results = {}
    for case, proc in procs.items():
        out, err = proc.communicate(timeout=120)
        results[case] = subprocess.CompletedProcess(proc.args, proc.returncode, out, err)
        results[case].path = paths.get(case)
    for sock in held:
        sock.close()
    return results


def one_line_error(result, code: int) -> str:
    assert result.returncode == code, (result.returncode, result.stdout, result.stderr)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr
    assert "Traceback" not in result.stderr and "SCENE INITIALIZED" not in result.stdout
    return lines[0]


def test_all_service_ports_busy_exits_1(failures):
    assert "cannot open the simulation's sockets" in one_line_error(failures["ports busy"], 1)


@pytest.mark.parametrize("case", ["garbage build", "old build"])
def test_bad_build_folders_exit_1(failures, case):
    assert "not a usable build folder" in one_line_error(failures[case], 1)


def test_invalid_scene_exits_2(failures):
    result = failures["invalid scene"]
    line = one_line_error(result, 2)
    assert str(result.path) in line and "translte" in line and "translate" in line  # where, what, a suggestion


def test_wait_for_client_starts_time_with_the_client_and_ends_the_run_when_it_leaves(tmp_path):
    """`morsec run --wait-for-client` (morsec sweep's runs): no frame before the client's first request, however
    long it takes to come; the simulation ends once it has left, printing how far it got; with --port-base 0 the
    lockstep port too is the OS's pick, so that runs side by side never meet."""
    from runtime_helpers import ServiceClient
    content = scene(environment={"stream_managers": {"socket": {"time_sync": True}}})
    build = build_folder(scene_file(tmp_path, content), tmp_path / "build")
    proc = subprocess.Popen([str(MORSEC), "run", str(build), "--duration", "30", "--port-base", "0",
                             "--service-port", "0", "--wait-for-client"], stdout=subprocess.PIPE, text=True,
                            cwd=tmp_path)
    try:
        lines = [proc.stdout.readline() for _ in range(3)]
        assert lines[0].strip() == "SCENE INITIALIZED"
        servers = dict(line.split()[:2] for line in lines[1:])
        assert not servers["lockstep"].endswith(":6000")
        time.sleep(0.5)  # half a second of wall clock, in fixed_step: not a frame
        client = ServiceClient(int(servers["services"].rpartition(":")[2]))
        assert client.ok("time", "statistics")["simulated_time"] == 0.0
        client.ok("time", "sleep", 0.5)
        assert client.ok("time", "statistics")["simulated_time"] >= 0.5
        client.sock.close()
        out, _ = proc.communicate(timeout=30)
    finally:
        proc.kill()
    assert proc.returncode == 0
    closing = out.splitlines()
    assert closing[-1] == "EXITING SIMULATION"
    simulated = float(closing[-2].split()[1])
    assert closing[-2].startswith("simulated ") and 0.5 <= simulated < 5.0 and "x real time)" in closing[-2]


def test_time_statistics_are_the_mean_and_variance_of_the_frames_wall_times():
    """`time statistics` (MORSE's mean_time, variance_time): the frames' wall-clock durations, here frames 20
    and 60 ms long in turn, measured around the clock's own ticks."""
    from morsec.runtime.clock import Clock

    clock = Clock(60.0, "fixed_step", 1.0, relative=True)
    durations = []
    last = time.perf_counter()
    clock.tick()  # the clock was made just before: its first frame lasts next to nothing
    for k in range(6):
        time.sleep(0.02 if k % 2 == 0 else 0.06)
        now = time.perf_counter()
        clock.tick()
        durations.append(now - last)
        last = now
    stats = clock.statistics()
    assert stats["frames"] == 7 and stats["simulated_time"] == pytest.approx(7 / 60)
    samples = [0.0, *durations]
    mean = sum(samples) / 7
    variance = sum((s - mean) ** 2 for s in samples) / 6
    assert stats["mean_time"] == pytest.approx(mean, rel=0.05)
    assert stats["variance_time"] == pytest.approx(variance, rel=0.1)
    assert stats["real_time_factor"] == pytest.approx((1 / 60) / mean, rel=0.05)
