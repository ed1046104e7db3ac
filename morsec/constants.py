"""Names and numbers fixed by MORSE's conventions, declared once."""

from typing import Literal

SEPARATOR = "."  # fully-qualified names: robot.child.grandchild
FORBIDDEN_NAME_CHARS = frozenset(". /\\\t\n\r")
DUPLICATE_SUFFIX = "_{:03d}"  # robot, robot_001, robot_002 ...

STREAM_PORT_BASE = 60000
SERVICE_PORT = 4000
SERVICE_PORT_ATTEMPTS = 10
SYNC_PORT = 6000
MULTINODE_PORT = 65000  # MORSE's multinode_server
DEFAULT_BIND = "127.0.0.1"
FOXGLOVE_PORT = 8765  # `morsec run --foxglove`: Foxglove's own default

DEFAULT_FREQUENCY = 60.0
TimeStrategy = Literal["best_effort", "fixed_step"]  # the scene's environment.time.strategy, `run --time-strategy`
DEFAULT_PHYSICS_SUBSTEPS = 8

PSEUDO_COMPONENTS = ("simulation", "time", "communication")

# ---- limits: what a client or a scene file may ask for, declared once (docs/running.md, docs/errors.md)
MAX_PORT = 65535
MIN_TIME_SCALE = 1e-3  # simulated seconds per wall-clock second: 1000x slower than real time at most
MAX_TIME_SCALE = 1e3  # ... and 1000x faster at most

# the socket protocol (services and streams)
MAX_JSON_DEPTH = 32  # nesting of [ and { in one request's parameters or one stream message
MAX_REQUEST_LINE = 4 * 1024 * 1024  # bytes of one service request line (its JSON included)
MAX_INPUT_LINE = 1024 * 1024  # bytes of one message to an actuator's stream
MAX_QUEUED_ANSWERS = 8 * 1024 * 1024  # bytes of answers waiting for a client that does not read: then dropped
MAX_REQUESTS_PER_POLL = 200  # request lines of one client handled per poll: the others wait their turn
MAX_PENDING_REQUESTS = 1000  # asynchronous requests (time sleep ...) one client may have running
# fixed_step, a client between two of its time sleeps (docs/running.md#time), wall-clock s: the loop follows the
# wall clock, SLEEP_HOLD_GRACE at most after the sleep ended; after a command from a client with no sleep running,
# or a message to an actuator stream, SLEEP_HOLD_WAIT at most. A new connection to an actuator stream is waited
# for SLEEP_HOLD_WAIT at most, for its first message
SLEEP_HOLD_WAIT = 0.2
SLEEP_HOLD_GRACE = 1.0
# fixed_step, numbered requests (pymorse's ids): a sleep counts from the frame the client's request numbered just
# before it arrived, if less than SLEEP_WITH_PREVIOUS s (wall) before; if it has not arrived, the sleep waits for
# it, SLEEP_ORDER_WAIT s at most
SLEEP_WITH_PREVIOUS = 0.1
SLEEP_ORDER_WAIT = 0.5
# MORSE's frame order (docs/running.md#time): a client's round trips since its last command, between two frames,
# each count a frame for its next sleep (MORSE read a client's requests once a frame), this many at most
ROUND_TRIPS_COUNTED = 6

# values a request may put into the physics (refused beyond, before they reach MuJoCo)
MAX_POSITION = 1e8  # m, or rad for joint angles: |coordinate| (Earth-scale: a geodetic teleport to the
# other side of the globe is 1.3e7 m from the scene origin, as MORSE's magnetometer test does)
MAX_SPEED = 1e4  # m/s or rad/s: |component of a velocity|
MAX_FORCE = 1e8  # N or N m: |component of a force or torque|

# scene files
MAX_SCENE_BYTES = 1024 * 1024  # PyYAML reads about a megabyte in seconds
MAX_SCENE_DEPTH = 64  # nesting of mappings and lists
MAX_SCENE_VALUES = 200_000  # values once YAML aliases are expanded
