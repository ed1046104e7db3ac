"""Streams and services of the scene, each given its endpoint by its middleware (ports, files): decided here,
once, recorded in the manifest; `middleware.json` is the same decisions as a middleware tool reads them."""

from __future__ import annotations

from morsec.middleware.base import StreamRequest
from morsec.middleware.registry import middleware, middlewares
from morsec.scene.manifest import ServiceEntry, StreamEntry


def assign_streams(components: list[tuple[str, str, list, tuple[str, ...], dict, tuple]]) -> list[StreamEntry]:
    """`components`: (fqn, default direction, the IR's stream specs, its type and the types it derives from,
    its resolved properties, its placement on its robot) of every component."""
    requests: dict[str, list[StreamRequest]] = {}
    for fqn, direction, specs, types, properties, placement in sorted(components, key=lambda c: c[0]):
        for spec in specs:
            options = spec.model_dump(exclude_none=True, exclude={"middleware", "direction"})
            requests.setdefault(spec.middleware, []).append(
                StreamRequest(fqn, spec.direction or direction, options, types, properties, placement))
    entries = []
    for name, streams in requests.items():
        for stream, endpoint in zip(streams, middleware(name).assign(streams)):
            entries.append(StreamEntry(component=stream.component, direction=stream.direction, middleware=name,
                                       endpoint=endpoint))
    return sorted(entries, key=lambda e: (e.component, e.middleware))


def assign_services(exposed: dict[str, list[str]], supervision: list[str]) -> list[ServiceEntry]:
    """`exposed`: component fqn -> middlewares its services go on; `supervision`: the middlewares serving the
    simulation's own services besides those that always serve them."""
    entries = []
    for name, cls in middlewares().items():
        components = sorted(fqn for fqn, names in exposed.items() if name in names)
        if cls.carries_services and (components or cls.always_serves or name in supervision):
            entries.append(ServiceEntry(middleware=name, endpoint=cls.services_endpoint(), components=components))
    return entries


def middleware_view(streams: list[StreamEntry], services: list[ServiceEntry], managers: dict) -> dict:
    """middleware.json: every endpoint, per middleware, for the tools that connect to them."""
    return {
        "streams": [{"component": s.component, "direction": s.direction, "middleware": s.middleware, **s.endpoint}
                    for s in streams],
        "services": {s.middleware: {**s.endpoint, "components": s.components} for s in services},
        "stream_managers": managers,
    }
