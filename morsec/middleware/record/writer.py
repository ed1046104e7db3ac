"""The writer process of a recording: reads what the loop's process sends on its standard input (`recorder`:
length-prefixed pickles: the start, then batches of messages) and writes the MCAP file it was handed (a file
descriptor), with the `mcap` package: each message as JSON on its stream's JSON channel and, converted by
`ros2` to CDR, on its ROS 2 channels. The file is finished (summary, footer) when
the standard input ends: when the run closes the recording, whether it ended normally, by SIGINT or SIGTERM
(the signals themselves are the run's to handle: this process ignores them), or by being killed.

    python -m morsec.middleware.record.writer FD PATH"""

from __future__ import annotations

import os
import pickle
import signal
import struct
import sys
from typing import Any, BinaryIO

from morsec import __version__
from morsec.middleware.record.channels import ROS2_DISTRIBUTION, Channel, StreamPlan

HEADER = struct.Struct("<I")  # the length of the pickle that follows


def read_frame(stream: BinaryIO) -> Any:
    """The next object sent, or None at the end of the input (a cut one included)."""
    head = stream.read(HEADER.size)
    if len(head) < HEADER.size:
        return None
    size = HEADER.unpack(head)[0]
    body = stream.read(size)
    return pickle.loads(body) if len(body) == size else None


class Recording:
    def __init__(self, out: BinaryIO, metadata: dict[str, dict[str, str]], plans: list[StreamPlan]):
        from mcap.writer import Writer
        from rosbags.typesys import Stores, get_typestore

        from morsec.middleware.record.ros2 import converter
        from morsec.middleware.socket_streams import encode
        self.encode = encode
        self.store = get_typestore(Stores(f"ros2_{ROS2_DISTRIBUTION}"))
        self.writer = Writer(out)
        self.writer.start(profile="", library=f"morsec {__version__}")
        for name, data in metadata.items():
            self.writer.add_metadata(name, data)
        self.schemas: dict[str, int] = {}
        self.channels: dict[tuple[str, str], int] = {}
        self.sequence: dict[int, int] = {}
        self.streams = []
        for plan in plans:
            ids = [self.channel(c) for c in plan.channels]
            conversions = [(converter(c.serialiser, self.store, c.endpoint), [ids[i] for i in c.channels])
                           for c in plan.conversions]
            self.streams.append((plan.component, ids[0], conversions))
        self.keys: list[tuple] = [()] * len(plans)
        self.failed: set[tuple[str, str]] = set()

    def channel(self, channel: Channel) -> int:
        key = (channel.topic, channel.schema)
        if key not in self.channels:
            if channel.schema not in self.schemas:
                if channel.encoding == "ros2msg":
                    text = self.store.generate_msgdef(channel.schema, ros_version=2)[0]
                else:
                    text = channel.schema_text
                self.schemas[channel.schema] = self.writer.register_schema(channel.schema, channel.encoding,
                                                                           text.encode("utf-8"))
            encoding = "cdr" if channel.encoding == "ros2msg" else "json"
            self.channels[key] = self.writer.register_channel(channel.topic, encoding, self.schemas[channel.schema])
        return self.channels[key]

    def write(self, channel: int, nanoseconds: int, data: bytes) -> None:
        sequence = self.sequence.get(channel, 0)
        self.sequence[channel] = sequence + 1
        self.writer.add_message(channel, nanoseconds, data, nanoseconds, sequence)

    def take(self, entry: tuple) -> None:
        """One entry of a batch (see recorder.Recorder.batch)."""
        if len(entry) == 2:
            self.keys[entry[0]] = entry[1]
        else:
            index, seconds, values = entry
            self.add(index, seconds, dict(zip(self.keys[index], pickle.loads(values))))

    def add(self, index: int, seconds: float, message: dict) -> None:
        component, json_channel, conversions = self.streams[index]
        nanoseconds = max(0, round(seconds * 1e9))
        self.write(json_channel, nanoseconds, self.encode(message)[:-1])
        for convert, channels in conversions:
            try:
                converted = convert.convert(message)
            except Exception as err:  # data the converter cannot read (a value of another type ...): said once
                key = (component, f"{type(err).__name__}: {err}")
                if key not in self.failed:
                    self.failed.add(key)
                    print(f"WARNING morsec.record: {component}: a message made no ROS 2 message, recorded as JSON "
                          f"only ({key[1]})", file=sys.stderr, flush=True)
                continue
            for channel, data in zip(channels, converted):
                if data is not None:
                    self.write(channel, nanoseconds, data)

    def finish(self) -> None:
        self.writer.finish()


def main(argv: list[str]) -> int:
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, signal.SIG_IGN)
    fd, path = int(argv[0]), argv[1]
    # the simulation first: on a machine whose cores are busy, the writer lags (the loop's process keeps what the
    # pipe does not take) and catches up when it can, at the latest at the end of the run
    os.nice(10)
    recording = None
    try:
        with os.fdopen(fd, "wb", buffering=1 << 20) as out:
            source = sys.stdin.buffer
            while (frame := read_frame(source)) is not None:
                if frame[0] == "batch":
                    for entry in frame[1]:
                        recording.take(entry)  # type: ignore[union-attr]
                elif frame[0] == "start":
                    recording = Recording(out, frame[1], frame[2])
            if recording is not None:
                recording.finish()
    except OSError as err:
        print(f"ERROR morsec.record: cannot write the recording {path}: {err.strerror or err}", file=sys.stderr,
              flush=True)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
