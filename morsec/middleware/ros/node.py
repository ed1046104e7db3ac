"""The simulation's ROS node (rospy, imported here only): its publishers and subscribers, /clock, /tf, and
the queue through which what arrives on rospy's threads (messages, action goals) reaches the loop's thread.

rospy runs its own threads: a subscriber's callback only converts the message and leaves it for the loop;
a goal is queued as a function the loop runs at its next flush (every frame), so that components and the
request manager are only ever touched by the loop's thread. One ROS simulation per process: rospy cannot
start a node again once it has shut one down."""

from __future__ import annotations

import heapq
import itertools
import logging
import queue
import time
import warnings
import xmlrpc.client
from collections.abc import Callable
from typing import Any

import rosgraph
import rospy
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage

from morsec.component.services import Request
from morsec.errors import RuntimeFailure
from morsec.middleware.ros.messages import ensure_messages

log = logging.getLogger("morsec.middleware.ros")

NODE_NAME = "morse"  # MORSE's node
MASTER_TIMEOUT = 3.0  # s to wait for the ROS master's answer at start
SEND_TIMEOUT = 1.0  # s a subscriber may leave a message unread before it is dropped


class RosNode:
    def __init__(self, context, settings: dict[str, Any]):
        ensure_messages()
        uri = rosgraph.get_master_uri()
        if not master_online(uri):
            raise RuntimeFailure(f"no ROS master answers at {uri} (ROS_MASTER_URI): start `roscore` first, or point "
                                 "ROS_MASTER_URI at a running one (docs/ros.md)")
        rospy.init_node(str(settings.get("node_name") or NODE_NAME), disable_signals=True)
        self.context = context
        self.pending: queue.SimpleQueue[Callable[[], None]] = queue.SimpleQueue()
        self.later: list[tuple[float, int, Callable[[], None]]] = []  # heap of (wall-clock deadline, n, fn)
        self.rows: list[tuple[str, str, str]] = []
        self.closables: list[Any] = []
        self.clock = self.publisher("/clock", Clock)
        self.last_clock: float | None = None
        self._tf: rospy.Publisher | None = None
        self._request_ids = 0
        self._order = itertools.count()

    # ---- the loop's side
    def call_soon(self, fn: Callable[[], None]) -> None:
        """Run `fn` on the loop's thread, at its next flush (from any thread)."""
        self.pending.put(fn)

    def call_later(self, seconds: float, fn: Callable[[], None]) -> None:
        """Run `fn` on the loop's thread `seconds` of wall-clock time from now (at a flush)."""
        heapq.heappush(self.later, (time.perf_counter() + seconds, next(self._order), fn))

    def flush(self) -> None:
        while True:
            try:
                fn = self.pending.get_nowait()
            except queue.Empty:
                break
            _run(fn)
        while self.later and self.later[0][0] <= time.perf_counter():
            _run(heapq.heappop(self.later)[2])
        now = self.context.now()
        if now != self.last_clock:
            self.last_clock = now
            if self.clock.listening:
                self.clock.publish(Clock(clock=rospy.Time.from_sec(now)))

    def call(self, component: str, service: str, args: list, done: Callable[[str, Any], None],
             client: Any) -> Request:
        """Call a component's service as a client would (on the loop's thread); `done(status, result)`."""
        self._request_ids += 1
        request = Request(f"ros{self._request_ids}", component, service, list(args),
                          reply=lambda _id, status, result: done(status, result), client=client)
        self.context.requests.handle(request)
        return request

    def cancel(self, client: Any, request: Request) -> None:
        self.context.requests.cancel(client, request.id)

    # ---- what streams and overlays open
    @property
    def tf(self) -> Publisher:
        if self._tf is None:
            self._tf = self.publisher("/tf", TFMessage)
        return self._tf

    def publisher(self, topic: str, message_class, latch: bool = False) -> Publisher:
        pub = Publisher(topic, message_class, latch)
        self.closables.append(pub)
        return pub

    def subscriber(self, topic: str, message_class, callback) -> rospy.Subscriber:
        sub = rospy.Subscriber(topic, message_class, callback, queue_size=1)
        self.closables.append(sub)
        return sub

    def open_stream(self, component: str, direction: str, endpoint: dict[str, Any]):
        from morsec.middleware.ros.conversions import stream_class
        stream = stream_class(endpoint["serialiser"])(self, component, endpoint)
        if endpoint["message"] == "tf2_msgs/TFMessage":  # a transform, on /tf whatever the topic
            where = f"/tf ({endpoint['frame_id']} -> {endpoint.get('child_frame_id')})"
        else:
            where = f"{endpoint['topic']} ({endpoint['message']})"
        self.rows.append((component, direction, where))
        return stream

    def open_overlay(self, component: str, instance: Any, overlay: str, params: dict[str, Any]) -> None:
        import importlib
        module, _, name = overlay.partition(":")
        cls = getattr(importlib.import_module(module), name)
        opened = cls(self, component, instance, **params)
        self.closables.append(opened)
        for what in opened.describe():
            self.rows.append((component, "", what))

    def describe(self) -> list[tuple[str, str, str]]:
        rows = [("ros master", "", rosgraph.get_master_uri()), ("ros clock", "", "/clock (simulated time)")]
        return rows + [(c, d or "ACT", w) for c, d, w in self.rows]

    def close(self) -> None:
        for item in reversed(self.closables):
            try:
                (getattr(item, "close", None) or item.unregister)()
            except Exception:
                pass
        self.closables = []
        rospy.signal_shutdown("morsec: the simulation ends")


def _run(fn: Callable[[], None]) -> None:
    try:
        fn()
    except Exception as err:  # a bad goal or message must not stop the simulation
        log.error("ROS: %s: %s", type(err).__name__, err)


class Publisher:
    """A topic published from the loop's thread, each message sent before `publish` returns (rospy's
    synchronous publishing): a frame's messages leave in the frame's order, before the next frame, whatever
    the time strategy (queued publishing hands them to one thread per subscriber, which a fixed_step loop
    leaves far behind). A subscriber that stops reading is dropped after SEND_TIMEOUT, never stalls the loop
    for longer; it may subscribe again."""

    def __init__(self, topic: str, message_class, latch: bool = False):
        with warnings.catch_warnings():  # rospy warns that queue_size=None publishes synchronously: it is meant
            warnings.simplefilter("ignore")
            self.pub = rospy.Publisher(topic, message_class, queue_size=None, latch=latch)
        self.latch = latch  # a latched message is kept for subscribers to come: published whoever listens
        self.connections = 0

    @property
    def listening(self) -> bool:
        count = self.pub.get_num_connections()
        if count != self.connections:
            self.connections = count
            for connection in list(getattr(self.pub.impl, "connections", ())):
                sock = getattr(connection, "socket", None)
                if sock is not None and sock.gettimeout() is None:
                    sock.settimeout(SEND_TIMEOUT)
        return count > 0

    def publish(self, message) -> None:
        if self.listening or self.latch:
            self.pub.publish(message)

    def unregister(self) -> None:
        self.pub.unregister()


def master_online(uri: str, timeout: float = MASTER_TIMEOUT) -> bool:
    import socket
    previous = socket.getdefaulttimeout()
    socket.setdefaulttimeout(timeout)
    try:
        code, _, _ = xmlrpc.client.ServerProxy(uri).getPid("/morsec")
        return code == 1
    except (OSError, xmlrpc.client.Error, ValueError):
        return False
    finally:
        socket.setdefaulttimeout(previous)
