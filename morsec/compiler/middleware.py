"""middleware.json: every stream and service of the scene, with its assigned port or file."""

from __future__ import annotations

from morsec.constants import SERVICE_PORT, STREAM_PORT_BASE


def middleware_config(scene, components: list[dict]) -> dict:
    """`components`: the manifest's component entries (fqn, kind, streams, services), any order."""
    streams = []
    explicit = {s["port"] for c in components for s in c["streams"] if s["middleware"] == "socket" and s["port"]}
    next_port = STREAM_PORT_BASE
    for comp in sorted(components, key=lambda c: c["fqn"]):
        for stream in comp["streams"]:
            entry = {"component": comp["fqn"], "direction": stream["direction"], "middleware": stream["middleware"]}
            if stream["middleware"] == "socket":
                entry["serializer"] = "json"
                if stream["port"]:
                    entry.update(port=stream["port"], explicit_port=True)
                else:
                    while next_port in explicit:
                        next_port += 1
                    entry.update(port=next_port, explicit_port=False)
                    next_port += 1
            elif stream["middleware"] == "text":
                fmt = stream.get("format") or "text"
                entry["serializer"] = fmt
                entry["file"] = stream.get("file") or f"{comp['fqn']}.{'csv' if fmt == 'csv' else 'txt'}"
            streams.append(entry)
    services = {c["fqn"]: c["services"] for c in sorted(components, key=lambda c: c["fqn"]) if c["services"]}
    env = scene.environment
    managers = {name: spec.model_dump(mode="json") for name, spec in sorted(env.stream_managers.items())}
    return {
        "service_port": SERVICE_PORT,
        "supervision": sorted(set(["socket", *env.services])),
        "services": services,
        "streams": streams,
        "stream_managers": managers,
    }
