from morsec.component import Sensor


class Clock(Sensor):
    """The simulated time, alone: its only field is `timestamp` (seconds since the Unix epoch, or since
    the start with relative time). Useful to drive a client's clock from the simulation."""

    short_descr = "Simulated time"
    builder_name = "Clock"
    frequency = 60.0
    data = ()


COMPONENT = Clock
