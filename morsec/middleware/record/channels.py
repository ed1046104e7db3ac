"""What a recorded stream becomes in the MCAP file: its channels, decided once when recording starts.

Every stream gets a JSON channel named by its component (`robot.pose`: a dotted name, never a ROS topic),
whose messages are the socket stream's JSON lines and whose schema is the component's message JSON Schema
(`morsec schema --messages`); `morsec replay` republishes these. A stream for which ROS has a message also gets
the ROS 2 channels of that message: the ROS middleware's serialiser (`ros.serialisers.SERIALISERS`: which
component is which message, the topic, the frames) is the one table, its ROS 1 type named the ROS 2 way
(`geometry_msgs/PoseStamped` -> `geometry_msgs/msg/PoseStamped`), on the topics the ROS middleware publishes
(a camera's `<topic>/image` and `<topic>/camera_info`, odometry's transform on `/tf`). A component with a ROS
stream in the scene is recorded as that stream (its serialiser, topic and frames); any other as the default
ROS stream of its type would be.

Standard library and the ROS table only: the loop's process decides the channels, the writer process imports
mcap and rosbags."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from morsec.middleware.base import StreamRequest
from morsec.middleware.ros.serialisers import SERIALISERS

JSON_SCHEMA_DIALECT = "https://json-schema.org/draft/2020-12/schema"
# the ROS 2 message definitions written into the file: rosbags' store of this distribution
ROS2_DISTRIBUTION = "jazzy"
TF = "tf2_msgs/msg/TFMessage"
# serialisers whose ROS message ROS 2 has in no package rosbags knows (control_msgs): recorded as JSON only
NO_ROS2 = frozenset({"joint_trajectory_controller_state"})
REQUESTS_TOPIC = "/morsec/requests"
ANSWERS_TOPIC = "/morsec/answers"


@dataclass(frozen=True)
class Channel:
    topic: str
    schema: str  # the schema's name: a ROS 2 type, or the JSON Schema's name
    encoding: str  # "ros2msg" (messages in CDR) or "jsonschema" (messages in JSON)
    schema_text: str = ""  # the JSON Schema; a ROS 2 definition is written by the writer, from rosbags


@dataclass(frozen=True)
class Conversion:
    """One ROS stream of a recorded stream: its serialiser, converting the data, and the ROS stream's endpoint
    (topic, frames, laser geometry); its messages go to `channels` (indices in the plan's channels)."""

    serialiser: str
    endpoint: dict[str, Any]
    channels: tuple[int, ...]


@dataclass(frozen=True)
class StreamPlan:
    """One recorded stream: its JSON channel first, then the ROS 2 channels its ROS streams fill."""

    component: str
    direction: str  # OUT: a sensor's messages; IN: the commands an actuator took
    channels: tuple[Channel, ...]
    conversions: tuple[Conversion, ...] = ()  # none: JSON only
    notes: tuple[str, ...] = ()  # why a ROS stream of it is recorded as JSON only


def ros2_type(ros1: str) -> str:
    """`geometry_msgs/PoseStamped` -> `geometry_msgs/msg/PoseStamped`."""
    package, name = ros1.split("/")
    return f"{package}/msg/{name}"


def ros2_outputs(serialiser: str, topic: str) -> tuple[tuple[str, str], ...]:
    """(topic, ROS 2 type) of each message a serialiser's ROS stream publishes, in the order its converter
    (`ros2.converter`) returns them."""
    entry = SERIALISERS[serialiser]
    if serialiser in NO_ROS2:
        return ()
    if serialiser in ("pose_tf", "static_tf"):
        return (("/tf", TF),)
    if serialiser == "static_tf2":
        return (("/tf_static", TF),)
    if serialiser == "image":
        return ((f"{topic}/image", "sensor_msgs/msg/Image"), (f"{topic}/camera_info", "sensor_msgs/msg/CameraInfo"))
    outputs = ((topic, ros2_type(entry.message)),)
    return outputs + ((("/tf", TF),) if entry.tf else ())


def ros_endpoints(request: StreamRequest, ros_streams: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The ROS streams a component is recorded as: the scene's own, else the default ROS stream of its type
    (none when ROS has no message for it)."""
    if ros_streams:
        return ros_streams
    from morsec.middleware.ros.middleware import Ros
    try:
        return Ros.assign([request])
    except ValueError:
        return []


def plan_stream(request: StreamRequest, schema_name: str, json_schema: dict[str, Any],
                ros_streams: list[dict[str, Any]]) -> StreamPlan:
    """The channels of one component's stream. `json_schema`: its message's JSON Schema; `ros_streams`: the
    endpoints of the component's ROS streams in the scene, if any."""
    import json

    from morsec.middleware.record.ros2 import CONVERTERS
    text = json.dumps({"$schema": JSON_SCHEMA_DIALECT, **json_schema}, ensure_ascii=False)
    channels = [Channel(request.component, schema_name, "jsonschema", text)]
    conversions, notes = [], []
    fields = json_schema.get("properties")
    for endpoint in ros_endpoints(request, ros_streams):
        name = endpoint["serialiser"]
        if SERIALISERS[name].direction != request.direction:
            continue
        outputs = ros2_outputs(name, endpoint["topic"])
        needs = CONVERTERS[name].needs if name in CONVERTERS else ()
        missing = [f for f in needs if fields is not None and f not in fields]
        if not outputs or missing:
            what = ros2_type(SERIALISERS[name].message)
            notes.append(f"recorded as JSON only: its messages have no {', '.join(missing)} for a {what}" if missing
                         else f"recorded as JSON only: ROS 2 has no {what} in the message packages morsec writes")
            continue
        indices = []
        for topic, ros_type in outputs:
            channel = Channel(topic, ros_type, "ros2msg")
            if channel not in channels:
                channels.append(channel)
            indices.append(channels.index(channel))
        conversions.append(Conversion(name, endpoint, tuple(indices)))
    return StreamPlan(request.component, request.direction, tuple(channels), tuple(conversions), tuple(notes))


def _schema(title: str, properties: dict[str, Any]) -> str:
    import json
    return json.dumps({"$schema": JSON_SCHEMA_DIALECT, "title": title, "type": "object", "properties": properties,
                       "required": sorted(properties)})


_REQUEST = {
    "client": {"type": "integer", "description": "the client's number in this recording (its connection)"},
    "id": {"type": "string", "description": "the request's id, as the client gave it"},
    "component": {"type": "string", "description": "the component (or simulation, time, communication)"},
    "service": {"type": "string"},
}
REQUESTS = Channel(REQUESTS_TOPIC, "morsec/service_request", "jsonschema", _schema(
    "a service request", {**_REQUEST, "args": {"type": "array", "description": "its arguments"}}))
ANSWERS = Channel(ANSWERS_TOPIC, "morsec/service_answer", "jsonschema", _schema(
    "the answer to a service request", {**_REQUEST, "status": {"enum": ["SUCCESS", "FAILED", "PREEMPTED"]},
                                         "result": {"description": "the service's result, or why it failed"}}))
