"""The keys held down in a viewer (`morsec run --view web|native`), for the components that read the keyboard
(MORSE's Keyboard actuator): the viewer's thread writes them, the simulation loop reads them."""

from __future__ import annotations

import threading
import time

# the keys components read, by their names here: MORSE's Keyboard's arrows and letters
KEYS = ("up", "down", "left", "right", "t", "g", "u", "o", "j", "l", "i", "k")
# a viewer that reports presses only (the native one: GLFW's key callback, repeated while a key is held) keeps a
# key down this long after its last press or repeat (the keyboard's repeat delay is about 0.25 to 0.5 s)
TAP_HOLD_S = 0.6


class KeyState:
    """Which of KEYS are down. `source` says which viewer feeds it (None: no viewer, the keyboard is not
    read)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._down: frozenset[str] = frozenset()
        self._tapped: dict[str, float] = {}
        self.source: str | None = None

    def set_down(self, keys) -> None:
        """The viewer's whole keyboard state: exactly these keys are down (web viewer, each frame)."""
        down = frozenset(k for k in keys if k in KEYS)
        with self._lock:
            self._down = down

    def tap(self, key: str) -> None:
        """A press (or the keyboard's repeat) of one key: it counts as down for TAP_HOLD_S."""
        if key in KEYS:
            with self._lock:
                self._tapped[key] = time.monotonic() + TAP_HOLD_S

    def held(self) -> frozenset[str]:
        now = time.monotonic()
        with self._lock:
            tapped = {k for k, until in self._tapped.items() if until > now}
            return self._down | tapped
