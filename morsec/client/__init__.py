"""A MORSE client with pymorse's API, for Python 3.11 and later: standard library only, no asyncore.

pymorse 1.4 (PyPI) cannot be imported on Python 3.12+ (it needs `asyncore`), and on 3.11 its `close()`
raises and leaves the process hanging (see `morsec.pymorse_compat`). This module speaks the same
socket protocol (docs/protocol.md) to `morsec run` or to MORSE itself, with the same API:

    from morsec.client import Morse

    with Morse() as sim:                              # localhost:4000; Morse("host", port)
        sim.robot.motion.publish({"v": 1.0, "w": 0.0})   # an actuator's stream
        sim.sleep(2.0)                                # simulated seconds (time sleep)
        print(sim.robot.pose.get()["x"])             # a sensor's next message
        sim.robot.motion.set_speed(0.0, 0.0).result()    # services return futures

- `Morse(host="localhost", port=4000)` discovers the scene with `simulation details`: robots are
  attributes (`sim.robot`, names made identifiers: `.`, `-`, `~` become `_`; also `sim["name"]`), and
  so are their components and sub-components (`sim.robot.arm.gripper`). Robots named `x`, `x_001`,
  `x_002`... are also the list `sim.xs`. `sim.robots` lists the robots' names (pymorse's quirk kept:
  robots named `robot`, `robot_001` make it that list of robots).
- A sensor's `get(timeout=None)` (the next message; None after the timeout), `last()` (the last one
  received, None before any; `last(n)` a list of up to 100), `subscribe(callback)`,
  `unsubscribe(callback)`; an actuator's `publish(dict)`. A stream connects on the first call of one
  of these. Callbacks run on one thread of the client's, in order, and may call services.
- A component's services are methods returning a `MorseFuture`: `result(timeout)`, `exception()`,
  `done()`, `running()`, `cancel()` (sends `<id> cancel`: `result()` then raises
  `MorseServicePreempted`), `add_done_callback(fn)`; comparing, printing or testing a future waits for
  its result, as in pymorse.
- `sim.rpc(component, service, *args)` (blocking), `rpc_t(timeout, ...)`, `rpc_async(...)` (a future),
  `sleep(seconds)`, `time()`, `reset()`, `activate(name)`, `deactivate(name)`, `streams()`,
  `get_stream_port(name)`, `cancel(request_id)`, `is_up()`, `spin()`, `quit()`, `close()`.
- Errors: `MorseServerError`, the base of `MorseServiceError` (a service that did not succeed:
  `MorseServiceFailed`, its message MORSE's; `MorseWrongArguments`, also a `TypeError` as in pymorse;
  `MorseServicePreempted`), `MorseConnectionError` (also a `ConnectionError`) and `MorseTimeoutError`
  (also a `TimeoutError`). Connecting to a port where nothing listens raises `ConnectionRefusedError`.

`close()` (the `with` block's end) sends what was published, waits for the requests still running
(or cancels them: `close(cancel_async_services=True)`, or a `with` block left on an exception), closes
the sockets and joins the client's threads; they are daemon threads, so a client never keeps a
process alive.

Running a pymorse script unchanged: `python -m morsec.client script.py [args]` runs it with
`import pymorse` bound to this module, in that process only.
"""

from .morse import (
    Component,
    Morse,
    MorseConnectionError,
    MorseFuture,
    MorseServerError,
    MorseServiceError,
    MorseServiceFailed,
    MorseServicePreempted,
    MorseTimeoutError,
    MorseWrongArguments,
    Robot,
    Stream,
    normalize_name,
)

__all__ = [
    "Component",
    "Morse",
    "MorseConnectionError",
    "MorseFuture",
    "MorseServerError",
    "MorseServiceError",
    "MorseServiceFailed",
    "MorseServicePreempted",
    "MorseTimeoutError",
    "MorseWrongArguments",
    "Robot",
    "Stream",
    "normalize_name",
]
