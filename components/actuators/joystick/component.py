"""MORSE's Joystick: drive the robot from a joystick or gamepad (Linux's joystick device, /dev/input/js<index>)."""

from __future__ import annotations

import errno
import logging
import os
import struct
from typing import Literal

from pydantic import Field

from morsec.component import Actuator, ComponentProperties

log = logging.getLogger("morsec.actuators.joystick")

# Linux's joystick API (linux/joystick.h): 8-byte events, time (ms), value (-32767 .. 32767), type, number
EVENT = struct.Struct("<IhBB")
JS_EVENT_BUTTON, JS_EVENT_AXIS, JS_EVENT_INIT = 0x01, 0x02, 0x80
AXIS_MAX = 32767.0


class JoystickBuilder:
    """MORSE's builder: Joystick(name=None, index=0), `index` the joystick to use (0 .. 7)."""

    def __init__(self, name=None, index=0):
        super().__init__(name)
        self.properties(index=int(index))


class Joystick(Actuator):
    """Moves its robot from a joystick, as MORSE's Joystick did from Blender's: the stick's first axis (left /
    right) turns the robot, its second (forward / back) drives it, each at `Speed` for a full push (forward
    and left positive; the turn rate is half of it, rad/s, as MORSE's). It reads Linux's joystick device
    `/dev/input/js<index>` (or `device`) without blocking, every tick. Where there is no such device it
    warns once and does nothing, so a MORSE script with a `Joystick()` runs anywhere."""

    short_descr = "Drive the robot from a joystick (/dev/input/js*)"
    builder_name = "Joystick"
    frequency = 60.0
    base_servo = True
    builder_mixin = JoystickBuilder

    class Properties(ComponentProperties):
        ControlType: Literal["Position", "Velocity", "Differential"] = Field(
            "Velocity", description="Velocity: the robot's body velocity is set; Position: it is displaced by "
            "speed / frequency each tick; Differential: as Velocity (MORSE drove the wheels)")
        Speed: float = Field(1.0, description="speed for a full push of the stick, m/s")
        index: int = Field(0, ge=0, le=7, description="which joystick: /dev/input/js<index>")
        device: str = Field("", description="the joystick device to read; empty: /dev/input/js<index>")

    data = ()

    def start(self) -> None:
        self.path = self.properties.device or f"/dev/input/js{self.properties.index}"
        self.axes: dict[int, int] = {}
        self.buttons: dict[int, int] = {}
        self._pending = b""
        try:
            self._fd: int | None = os.open(self.path, os.O_RDONLY | os.O_NONBLOCK)
        except OSError as err:
            self._fd = None
            log.warning("%s: no joystick at %s (%s): the joystick does nothing", self.name, self.path,
                        err.strerror or err)

    def finalize(self) -> None:
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None

    def _read_events(self) -> None:
        while self._fd is not None:
            try:
                chunk = os.read(self._fd, EVENT.size * 64)
            except BlockingIOError:
                return
            except OSError as err:
                if err.errno == errno.EAGAIN:
                    return
                log.warning("%s: %s: %s; the joystick stops", self.name, self.path, err.strerror or err)
                os.close(self._fd)
                self._fd = None
                return
            if not chunk:
                return  # a pipe whose writer is gone: nothing more for now
            data = self._pending + chunk
            whole = len(data) - len(data) % EVENT.size
            for _, value, kind, number in EVENT.iter_unpack(data[:whole]):
                table = self.axes if kind & ~JS_EVENT_INIT == JS_EVENT_AXIS else self.buttons
                table[number] = value
            self._pending = data[whole:]

    def default_action(self) -> None:
        if self._fd is None:
            return
        self._read_events()
        factor = -self.properties.Speed / AXIS_MAX
        turn = self.axes.get(0, 0) * factor  # stick left (negative) turns left
        forward = self.axes.get(1, 0) * factor  # stick forward (negative) drives forward
        control = "Velocity" if self.properties.ControlType == "Differential" else self.properties.ControlType
        self.robot.apply_speed(control, [forward, 0.0, 0.0], [0.0, 0.0, turn / 2.0], self.frequency)


COMPONENT = Joystick
