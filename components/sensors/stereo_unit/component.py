"""MORSE's StereoUnit: a mount grouping cameras, moved as one, captured together."""

import logging

from morsec.component import ComponentProperties, Sensor, async_service

log = logging.getLogger("morsec.sensors.stereo_unit")


class StereoUnit(Sensor):
    """A mount for cameras: the cameras appended to it (its child components, e.g. two video_cameras
    0.4 m apart) move with it — put it on a pan-tilt unit to turn them together — and its asynchronous
    service `capture(n)` makes every one of them grab n pictures, answering when the last one is done.
    It measures nothing itself: its messages carry only the timestamp."""

    short_descr = "Mount grouping cameras: they move together, capture(n) drives them all"
    builder_name = "StereoUnit"
    frequency = 60.0

    class Properties(ComponentProperties):
        pass

    data = ()

    def start(self) -> None:
        self.cameras = [c.instance for c in self.sim.components
                        if c.parent == self.name and hasattr(c.instance, "start_capture")]
        if not self.cameras:
            log.warning("%s: no camera appended to this stereo unit", self.name)
        self._expected = 0

    @async_service
    def capture(self, n: int) -> None:
        """Make each camera of the unit grab `n` pictures; answers SUCCESS when all of them are done."""
        if not self.cameras:
            raise ValueError(f"{self.name} has no camera: append cameras to it in the scene")
        self._expected = len(self.cameras)
        for camera in self.cameras:
            camera.start_capture(n, self._one_done)

    def _one_done(self) -> None:
        self._expected -= 1
        if self._expected == 0:
            self.completed("SUCCESS")

    def interrupt(self) -> None:
        self._expected = 0
        for camera in self.cameras:
            camera.interrupt()


COMPONENT = StereoUnit
