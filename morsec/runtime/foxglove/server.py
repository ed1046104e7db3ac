"""The Foxglove WebSocket server of a running simulation (foxglove-sdk's, in its own threads): the
components' streams (`streams`), and, from the loop at most WORLD_RATE times per wall-clock second, the
simulated time (Foxglove's clock follows it) and every body's transform on `/tf`; the scene's geometry on
`/scene` whenever a client subscribes to it. Nothing is converted or sent for a channel nobody subscribed to."""

from __future__ import annotations

import time

import foxglove
from foxglove.channels import FrameTransformsChannel, SceneUpdateChannel
from foxglove.websocket import Capability, ServerListener

from morsec.errors import RuntimeFailure
from morsec.runtime.foxglove.streams import FoxgloveStream, nanoseconds, streams_for
from morsec.runtime.foxglove.world import BodyFrames, SceneGeometry

TF_TOPIC = "/tf"
SCENE_TOPIC = "/scene"
WORLD_RATE = 50.0  # transforms and time per wall-clock second, at most (a fixed_step loop runs far faster)


class _Subscriptions(ServerListener):
    """foxglove-sdk's server listener: notes, from the server's thread, that a client subscribed to /scene."""

    def __init__(self):
        self.scene_wanted = False

    def on_subscribe(self, client, channel) -> None:
        if channel.topic == SCENE_TOPIC:
            self.scene_wanted = True


class FoxgloveServer:
    def __init__(self, model, bind: str, port: int, name: str):
        self.context = foxglove.Context()
        self.subscriptions = _Subscriptions()
        try:
            self.server = foxglove.start_server(name=name, host=bind, port=port, capabilities=[Capability.Time],
                                                server_listener=self.subscriptions, context=self.context)
        except RuntimeError as err:  # FoxgloveError: Failed to bind port: Address already in use (os error 98)
            reason = str(err).rsplit(": ", 1)[-1]
            raise RuntimeFailure(f"--foxglove: cannot serve on {bind}:{port}: {reason} (--foxglove-port picks "
                                 "another port, 0 one the OS picks)") from None
        self.bind = bind
        self.frames = BodyFrames(model)
        self.geometry = SceneGeometry(model)
        self.tf = FrameTransformsChannel(TF_TOPIC, context=self.context)
        self.scene = SceneUpdateChannel(SCENE_TOPIC, context=self.context)
        self.streams: list[FoxgloveStream] = []
        self._period = 1.0 / WORLD_RATE
        self._next = 0.0

    @property
    def url(self) -> str:
        return f"ws://{self.bind}:{self.server.port}"

    @property
    def app_url(self) -> str:
        """Foxglove's web app with this server as its data source."""
        return self.server.app_url() or ""

    def streams_for(self, fqn: str, cls, level: str | None, properties) -> list[FoxgloveStream]:
        made = streams_for(self.context, fqn, cls, level, properties)
        self.streams.extend(made)
        return made

    def frame(self, data, seconds: float) -> None:
        """Called whenever the loop sends what is queued: the time and the transforms (at most WORLD_RATE times
        per wall-clock second), and the scene to a client that has just subscribed to it."""
        now = time.perf_counter()
        if now < self._next:
            return
        self._next = now + self._period
        self.server.broadcast_time(nanoseconds(seconds))
        if self.tf.has_sinks():
            self.tf.log(self.frames.message(data, seconds), log_time=nanoseconds(seconds))
        if self.subscriptions.scene_wanted:
            self.subscriptions.scene_wanted = False
            self.scene.log(self.geometry.message(seconds), log_time=nanoseconds(seconds))

    def close(self) -> None:
        for stream in self.streams:
            stream.close()
        self.tf.close()
        self.scene.close()
        self.server.stop()
