"""The `ros` middleware as the registry and the compiler see it: its stream options, the endpoint (topic,
serialiser, frames) of each stream, the overlays it has; at run time it starts the simulation's ROS node
(`node`), which imports rospy."""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from morsec.middleware.base import Middleware, StreamRequest
from morsec.middleware.ros.available import require_ros, ros_folder, ros_problem
from morsec.middleware.ros.serialisers import MORSE, default_topic, serialiser_for

# MORSE's overlays morsec has: {MORSE's class path: (morsec's class, the component types it adapts, the message
# package it needs beyond the middleware's own and its Debian package)}
OVERLAYS = {
    MORSE + "overlays.armatures.ArmatureController": ("morsec.middleware.ros.overlays:ArmatureController",
                                                       ("armature",), None),
    MORSE + "overlays.waypoints.WayPoint": ("morsec.middleware.ros.overlays:WayPoint", ("waypoint",),
                                            ("move_base_msgs", "python3-move-base-msgs")),
}
# what a laser scan message needs of its sensor's properties
LASER_GEOMETRY = ("laser_range", "scan_window", "resolution")


def _findable(module: str) -> bool:
    """Importable as things are, or from ROS's folder (which only a simulation adds to sys.path)."""
    folder = ros_folder()
    return (importlib.util.find_spec(module) is not None
            or (os.path.isdir(folder) and importlib.machinery.PathFinder.find_spec(module, [folder]) is not None))


class Ros(Middleware):
    name = "ros"
    description = "ROS 1: a topic per stream (MORSE's names and messages), actions through overlays, /clock, tf"
    carries_services = True

    class Options(BaseModel):
        model_config = ConfigDict(defer_build=True)  # read by a build, not by a run
        child_frame_id: str | None = Field(
            None, description="ros: the moving frame of an odometry or tf stream (default MORSE's: /base_footprint, "
            "/base_link)")
        parent_frame_id: str | None = Field(
            None, description="ros: the robot's frame a static tf stream (StaticTFPublisher) places the component in "
            "(default base_link)")

    # ---- build time
    @classmethod
    def unavailable(cls) -> str | None:
        return ros_problem("the ROS middleware")

    @classmethod
    def check_stream(cls, request: StreamRequest) -> str | None:
        try:
            serialiser_for(request.types, request.direction, request.options.get("method"))
        except ValueError as err:
            return str(err)
        return None

    @classmethod
    def overlay_class(cls, overlay: str, types: tuple[str, ...]) -> str:
        if overlay not in OVERLAYS:
            from morsec.errors import did_you_mean
            raise ValueError(f"the ros middleware has no overlay {overlay!r}{did_you_mean(overlay, OVERLAYS)} "
                             f"(it has: {', '.join(sorted(OVERLAYS))})")
        target, adapts, needs = OVERLAYS[overlay]
        if not set(adapts) & set(types):
            raise ValueError(f"overlay {overlay} adapts {' or '.join(adapts)} components, not "
                             f"{types[0] if types else 'this one'}")
        if needs and ros_problem() is None and not _findable(needs[0]):
            raise ValueError(f"overlay {overlay} needs ROS's {needs[0]}: install it with `sudo apt-get install "
                             f"{needs[1]}`")
        return target

    @classmethod
    def assign(cls, streams: list[StreamRequest]) -> list[dict[str, Any]]:
        endpoints = []
        for stream in streams:
            serialiser = serialiser_for(stream.types, stream.direction, stream.options.get("method"))
            topic = stream.options.get("topic") or default_topic(stream.component)
            endpoint: dict[str, Any] = {
                "topic": topic,
                "serialiser": serialiser.name,
                "message": serialiser.message,
                "frame_id": stream.options.get("frame_id") or serialiser.frame_id or topic,
            }
            child = stream.options.get("child_frame_id") or serialiser.child_frame_id
            if child:
                endpoint["child_frame_id"] = child
            if serialiser.name in ("static_tf", "static_tf2"):  # the component on its robot, as placed
                endpoint["parent_frame_id"] = stream.options.get("parent_frame_id") or "base_link"
                endpoint["placement"] = [list(part) for part in stream.placement]
            if serialiser.name == "laser_scan":
                endpoint["geometry"] = {k: stream.properties[k] for k in LASER_GEOMETRY if k in stream.properties}
            endpoints.append(endpoint)
        return endpoints

    # ---- run time
    def __init__(self, context, settings):
        super().__init__(context, settings)
        require_ros("the ROS middleware")
        from morsec.middleware.ros.node import RosNode
        self.node = RosNode(context, settings)

    def open_stream(self, component: str, direction: str, endpoint: dict[str, Any]):
        return self.node.open_stream(component, direction, endpoint)

    def open_services(self, endpoint: dict[str, Any]) -> None:
        """MORSE's ROS request manager served only services with a ROS type, which its overlays declared: a
        component's own services are reached through its overlays (add_overlay)."""

    def open_overlay(self, component: str, instance: Any, overlay: str, params: dict[str, Any]) -> None:
        self.node.open_overlay(component, instance, overlay, params)

    def flush(self) -> None:
        self.node.flush()

    def describe(self) -> list[tuple[str, str, str]]:
        return self.node.describe()

    def close(self) -> None:
        self.node.close()
