"""CDR, as ROS 2 serialises its messages (little endian, XCDR1: each primitive aligned on its size, counted from
after the 4-byte encapsulation header; a string is its uint32 length with the NUL, its bytes, the NUL), for the
messages whose layout is fixed once a stream's frame ids are known (a pose, odometry, a transform ...): one
`struct.Struct` per stream and message, packed in one call. rosbags' serialiser builds a message object
per field, several times the cost, which the writer process could not afford at the loop's pace; it still
serialises the messages of variable size (scans, images, joint states). Tests decode both with rosbags and
with mcap-ros2-support."""

from __future__ import annotations

import struct

ENCAPSULATION = b"\x00\x01\x00\x00"  # CDR, little endian


class Layout:
    """The struct format of one message, field by field in the definition's order."""

    def __init__(self) -> None:
        self.format = ["<"]
        self.offset = 0

    def align(self, size: int) -> None:
        padding = -self.offset % size
        if padding:
            self.format.append(f"{padding}x")
            self.offset += padding

    def add(self, code: str, count: int = 1) -> Layout:
        """`count` primitives of struct code `code` (d: float64, i: int32, I: uint32, b: int8, H: uint16, B: uint8)."""
        size = struct.calcsize("<" + code)
        self.align(size)
        self.format.append(f"{count}{code}")
        self.offset += size * count
        return self

    def string(self, text: str) -> tuple[int, bytes]:
        """A string known in advance: the two values to pack for it (its length, its bytes)."""
        data = text.encode("utf-8") + b"\0"
        self.add("I")
        self.format.append(f"{len(data)}s")
        self.offset += len(data)
        return len(data), data

    def header(self, frame_id: str) -> tuple[int, bytes]:
        """std_msgs/Header: builtin_interfaces/Time (int32 sec, uint32 nanosec), then the frame id."""
        self.add("i").add("I")
        return self.string(frame_id)

    def struct(self) -> struct.Struct:
        return struct.Struct("".join(self.format))
