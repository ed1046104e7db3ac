"""Names and numbers fixed by MORSE's conventions, declared once."""

SEPARATOR = "."  # fully-qualified names: robot.child.grandchild
FORBIDDEN_NAME_CHARS = frozenset(". /\\\t\n\r")
DUPLICATE_SUFFIX = "_{:03d}"  # robot, robot_001, robot_002 ...

STREAM_PORT_BASE = 60000
SERVICE_PORT = 4000
SERVICE_PORT_ATTEMPTS = 10
SYNC_PORT = 6000
DEFAULT_BIND = "127.0.0.1"

DEFAULT_FREQUENCY = 60.0
DEFAULT_PHYSICS_SUBSTEPS = 8

PSEUDO_COMPONENTS = ("simulation", "time", "communication")
