"""MORSE's Sound: a sound attached to the robot, played, paused or stopped on command."""

from __future__ import annotations

import logging
import os
from pathlib import Path
from typing import Literal

from pydantic import Field

from morsec.component import Actuator, ComponentProperties, DataField, service

log = logging.getLogger("morsec.actuators.sound")


class SoundBuilder:
    """MORSE's builder: Sound(name=None), `open(filepath)` the sound file (an error if it does not exist)."""

    def open(self, filepath):
        with open(filepath, "rb"):  # as MORSE's builder: a missing file stops the script
            pass
        self.properties(file=os.path.abspath(str(filepath)))


class Sound(Actuator):
    """A sound source on the robot, MORSE's Sound actuator: its `mode` (streamed in, or set by the `play`,
    `pause`, `stop` services) says whether the sound is playing. morsec has no audio output: the sound's state
    is kept, reported (`get_status`: mode, file, playing time) and logged when it changes, so that a MORSE
    script with a Sound runs and a client can follow what would be heard."""

    short_descr = "Sound source: play, pause, stop (state kept; no audio output)"
    builder_name = "Sound"
    frequency = 60.0
    builder_mixin = SoundBuilder

    class Properties(ComponentProperties):
        mode: Literal["play", "pause", "stop"] = Field("play", description="the state at start (MORSE's builder "
                                                       "sets 'play')")
        file: str = Field("", description="the sound file (builder: sound.open(path)); recorded")

    data = (DataField("mode", "play", "str", "play, pause or stop"),)

    def start(self) -> None:
        self.local_data["mode"] = self.properties.mode
        self._mode = None
        self.played = 0.0  # s of playing since the last stop
        if self.properties.file and not Path(self.properties.file).is_file():
            log.warning("%s: sound file %s not found", self.name, self.properties.file)

    def default_action(self) -> None:
        mode = str(self.local_data.get("mode", "play"))
        if mode not in ("play", "pause", "stop"):
            log.warning("%s: mode %r ignored (play, pause or stop)", self.name, mode)
            self.local_data["mode"] = mode = self._mode or "stop"
        if mode != self._mode:
            log.info("%s: %s %s", self.name, mode, self.properties.file or "(no file)")
            self._mode = mode
        if mode == "play":
            self.played += 1.0 / self.frequency
        elif mode == "stop":
            self.played = 0.0

    @service
    def play(self) -> None:
        """Start (or resume) the sound."""
        self.local_data["mode"] = "play"

    @service
    def pause(self) -> None:
        """Pause the sound; `play` resumes it."""
        self.local_data["mode"] = "pause"

    @service
    def stop(self) -> None:
        """Stop the sound; `play` starts it from the beginning."""
        self.local_data["mode"] = "stop"

    @service
    def get_status(self) -> dict:
        """{mode, file, played}: the state, the sound file and how long it has played since it was last
        stopped, s of simulated time."""
        return {"mode": self._mode or self.local_data["mode"], "file": self.properties.file,
                "played": round(self.played, 6)}


COMPONENT = Sound
