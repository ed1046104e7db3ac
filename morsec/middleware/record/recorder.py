"""The loop's side of a recording. Converting a message to ROS 2 and writing it to MCAP costs the loop's thread
more than a frame of a small scene costs, and a thread of the same process would take that time from the loop
all the same (the interpreter runs one thread at a time, and handing it over between threads costs the loop
more on a busy machine): the work is done by a writer process (`writer`).

The loop only copies each message as it is published (sensors reuse their data dicts): its values, pickled
(its keys are sent when they change: a stream's keys are the same message after message), half of what
pickling the dict costs (an OrderedDict pickles through Python code).
Every BATCH messages, BATCH_BYTES or BATCH_AGE wall-clock seconds, the batch is pickled and written to the
writer's pipe without blocking: what the pipe does not take waits in memory and goes at the next batch, so
that the loop does not wait for a writer that lags behind until MAX_PENDING bytes wait. The writer runs at a
lower priority (nice 10): on a machine whose cores are all busy it is the one that lags, not the loop.
Closing the recording sends what is left and waits for the writer to finish the file."""

from __future__ import annotations

import functools
import logging
import os
import pickle
import subprocess
import sys
import time
from collections import deque
from collections.abc import Callable
from itertools import count
from pathlib import Path
from typing import Any

from morsec.errors import MorsecError, RuntimeFailure
from morsec.middleware.record.channels import ANSWERS, REQUESTS, StreamPlan
from morsec.middleware.record.writer import HEADER

log = logging.getLogger("morsec.record")

BATCH = 512  # messages per write to the writer's pipe
BATCH_AGE = 0.5  # s of wall time a message waits at most before it is sent
BATCH_BYTES = 4 << 20  # or this many bytes of messages (cameras)
MAX_PENDING = 256 << 20  # bytes waiting for the writer beyond which the loop waits for it
PIPE_SIZE = 1 << 20  # the pipe's buffer
CLOSE_TIMEOUT = 120.0  # s the run waits, at its end, for the writer to finish the file
F_SETPIPE_SZ = 1031  # Linux's fcntl


class Recorder:
    def __init__(self, path: Path, now: Callable[[], float], plans: list[StreamPlan],
                 metadata: dict[str, dict[str, str]], services: bool = False):
        """`now`: the simulated time messages are logged at; `plans`: the streams (their index in the list is
        their number); `services`: also record service requests and answers (see watch)."""
        self.path = Path(path)
        self.now = now
        self.plans = list(plans)
        if services:
            self.plans += [StreamPlan(REQUESTS.topic, "OUT", (REQUESTS,)), StreamPlan(ANSWERS.topic, "OUT", (ANSWERS,))]
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            out = open(self.path, "wb")
        except OSError as err:
            raise MorsecError(f"cannot write the recording {self.path}: {err.strerror or err}") from None
        with out:
            # a session of its own: a Ctrl-C at the terminal, or a signal to the run's process group, stops the
            # run, which then closes the recording; the writer ends when its input does
            self.process = subprocess.Popen([sys.executable, "-m", "morsec.middleware.record.writer",
                                             str(out.fileno()), str(self.path)],
                                            stdin=subprocess.PIPE, pass_fds=(out.fileno(),), start_new_session=True)
        self.pipe = self.process.stdin
        try:
            import fcntl
            fcntl.fcntl(self.pipe.fileno(), F_SETPIPE_SZ, PIPE_SIZE)
        except (ImportError, OSError):
            pass
        self.fd = self.pipe.fileno()
        os.set_blocking(self.fd, False)
        self.pending: deque[memoryview] = deque()  # what the pipe has not taken yet
        self.pending_bytes = 0
        self.batch: list[tuple] = []  # (index, time, its values pickled) | (index, its keys from now on)
        self.keys: list[tuple | None] = [None] * len(self.plans)  # each stream's keys, as the writer last heard them
        self.batch_bytes = 0
        self.oldest = 0.0
        self.failed = False
        self.unrecordable: set[int] = set()  # streams whose message could not be copied (said once)
        self.clients: dict[Any, int] = {}
        self.numbers = count(1)
        self._send(("start", metadata, self.plans))

    # ---- streams
    def stream(self, index: int) -> RecordedStream:
        return RecordedStream(self, index)

    def add(self, index: int, message: dict) -> None:
        """Queue one message of stream `index`, logged at its timestamp (a sensor's: the simulated time it was
        measured at, which is now) or now (an actuator's command, a service's request)."""
        if not self.batch:
            self.oldest = time.perf_counter()
        when = message.get("timestamp")
        if when.__class__ is not float:
            when = self.now()
        keys = tuple(message)
        if keys != self.keys[index]:
            self.keys[index] = keys
            self.batch.append((index, keys))
        try:
            payload = pickle.dumps(tuple(message.values()), protocol=5)
        except Exception as err:  # a value pickle cannot copy (a component's own object): not recorded
            if index not in self.unrecordable:
                self.unrecordable.add(index)
                log.error("%s: a message was not recorded: %s: %s", self.plans[index].component,
                          type(err).__name__, err)
            return
        self.batch.append((index, when, payload))
        self.batch_bytes += len(payload)
        if (len(self.batch) >= BATCH or self.batch_bytes >= BATCH_BYTES
                or time.perf_counter() - self.oldest >= BATCH_AGE):
            self.flush()

    def flush(self) -> None:
        if self.batch:
            batch, self.batch, self.batch_bytes = self.batch, [], 0
            self._send(("batch", batch))

    def _send(self, frame: Any) -> None:
        if self.failed or self.pipe is None:  # stopped, or closed (its descriptor may be another file's now)
            return
        body = pickle.dumps(frame, protocol=5)
        self.pending.append(memoryview(HEADER.pack(len(body)) + body))
        self.pending_bytes += len(self.pending[-1])
        self._write()
        if self.pending_bytes > MAX_PENDING:  # the writer is far behind: wait for it
            self._write(block=True)

    def _write(self, block: bool = False) -> None:
        """Write what is pending to the pipe, as much as it takes (all of it if `block`)."""
        if block:
            os.set_blocking(self.fd, True)
        try:
            while self.pending:
                try:
                    written = os.write(self.fd, self.pending[0])
                except BlockingIOError:
                    return
                self.pending_bytes -= written
                if written == len(self.pending[0]):
                    self.pending.popleft()
                else:
                    self.pending[0] = self.pending[0][written:]
        except OSError:  # the writer stopped (it said why on stderr): the run says so when it ends
            self.failed = True
            self.pending.clear()
        finally:
            if block and not self.failed:
                os.set_blocking(self.fd, False)

    # ---- services
    def watch(self, on_request: list) -> None:
        """Record every service request, and its answer, from the request manager's `on_request` hook."""
        requests, answers = len(self.plans) - 2, len(self.plans) - 1

        def heard(request) -> None:
            if request.client not in self.clients:
                self.clients[request.client] = next(self.numbers)
            client = self.clients[request.client]
            about = {"client": client, "id": str(request.id), "component": request.component,
                     "service": request.service}
            self.add(requests, {**about, "args": list(request.args)})
            reply = request.reply

            def answer(request_id, status, result) -> None:
                reply(request_id, status, result)
                self.add(answers, {**about, "status": status, "result": result})

            request.reply = answer

        on_request.append(heard)

    def forget(self, client: Any) -> None:
        self.clients.pop(client, None)

    def close(self) -> None:
        """Send what is left, and wait until the writer has finished the file."""
        if self.pipe is None:
            return
        self.flush()
        if not self.failed:
            self._write(block=True)
        try:
            self.pipe.close()
        except OSError:
            pass
        self.pipe = None
        try:
            code = self.process.wait(CLOSE_TIMEOUT)
        except subprocess.TimeoutExpired:
            self.process.kill()
            code = self.process.wait()
        if code != 0 or self.failed:
            raise RuntimeFailure(f"the recording {self.path} is incomplete: its writer ended with code {code} "
                                 "(its error is above)")


class RecordedStream:
    """A stream's tap: always listening (the sensor's message is built for the recording whoever else reads)."""

    listening = True

    def __init__(self, recorder: Recorder, index: int):
        self.publish = functools.partial(recorder.add, index)  # the loop calls it: one call, not two

    def close(self) -> None:
        pass
