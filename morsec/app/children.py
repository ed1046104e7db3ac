"""Child processes that do not outlive the process that started them."""

from __future__ import annotations

import ctypes
import signal
import sys


def _die_with_parent() -> None:  # pragma: no cover - runs in the child, between fork and exec
    """Linux: the child gets SIGTERM when the thread that started it ends (a killed test run, a lost worker)."""
    try:
        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


# subprocess.Popen(preexec_fn=...): None where prctl does not exist
die_with_parent = _die_with_parent if sys.platform.startswith("linux") else None
