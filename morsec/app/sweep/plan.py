"""From a sweep file to the runs it asks for: its variants (explicit variants crossed with the grid's
product), each variant's scene (the values set at their paths, the metrics' sensors added), built once per
distinct scene (cached by content), and one run per variant and seed.

Every mistake is found here, before anything runs: a path the scene does not have, a value the scene refuses,
a robot, sensor or zone the metrics name that the scene lacks. Each is reported at its place in the sweep
file."""

from __future__ import annotations

import copy
import hashlib
import itertools
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from morsec.app import buildcache
from morsec.app.sweep import instrument
from morsec.app.sweep.paths import PathError, set_value
from morsec.app.sweep.spec import MAX_RUNS, Sweep
from morsec.errors import MorsecError, SceneError, yaml_path

BUILDS = "builds"


@dataclass
class Variant:
    id: str  # 'v' and a hash of its values: the same values, the same id, whatever the order in the file
    values: dict[str, Any]  # scene path (as written) -> value
    where: dict[str, tuple]  # scene path -> where its value is written in the sweep file
    build: Path | None = None
    build_key: str = ""


@dataclass
class RunTask:
    """One run, all a worker needs (it is pickled to Dask workers): which build, which seed, how long, how it
    is judged."""

    run: str
    variant: str
    seed: int
    values: dict[str, Any]
    build_key: str
    build_dir: str
    duration: float
    timeout: float
    client: str | None
    client_cwd: str
    metrics: list[dict] = field(default_factory=list)


def variants_of(sweep: Sweep) -> list[Variant]:
    """Explicit variants (or one empty variant) crossed with every combination of the grid, in the file's
    order; two that set the same values are one."""
    spec = sweep.spec
    explicit = spec.variants or [{}]
    grid_keys = list(spec.grid)
    for i, variant in enumerate(spec.variants):
        for key in variant:
            if key in spec.grid:
                raise sweep.error(f"{key!r} is also in grid: a path is varied by the grid or by variants, not both",
                                  "variants", i, key, key=True)
    combos = list(itertools.product(*(range(len(spec.grid[k])) for k in grid_keys)))
    count = len(explicit) * len(combos) * len(spec.seeds)
    if count > MAX_RUNS:
        raise sweep.error(f"{count} runs: more than {MAX_RUNS}; split the sweep")
    found: dict[str, Variant] = {}
    for i, variant in enumerate(explicit):
        for combo in combos:
            values = dict(variant)
            where = {k: ("variants", i, k) for k in variant}
            for key, index in zip(grid_keys, combo):
                values[key] = spec.grid[key][index]
                where[key] = ("grid", key, index)
            vid = variant_id(values)
            found.setdefault(vid, Variant(vid, values, where))
    return list(found.values())


def variant_id(values: dict[str, Any]) -> str:
    text = json.dumps(values, sort_keys=True, separators=(",", ":"))
    return "v" + hashlib.sha256(text.encode("utf-8")).hexdigest()[:8]


def plan(sweep: Sweep, out: Path) -> tuple[list[Variant], list[RunTask]]:
    """The variants, each built into `out`/builds/<key> (compiled only when not built already), and the runs."""
    from morsec.component.catalogue import load_catalogue
    from morsec.frontends.text import read_scene_file
    scene = sweep.scene
    if not scene.is_file():
        raise sweep.error(f"no such scene file {str(scene)!r}", "scene")
    if scene.suffix not in buildcache.CACHED_SUFFIXES:
        raise sweep.error("a sweep's scene is a YAML or TOML file (a builder script converts to one: "
                          f"morsec convert {sweep.spec.scene} -o scene.yaml)", "scene")
    base, smap = read_scene_file(scene)
    inputs = buildcache.inputs_key(scene) or ""
    cat = load_catalogue(scene.parent)
    variants = variants_of(sweep)
    instrument.check(sweep, base, cat)
    for variant in variants:
        data = copy.deepcopy(base)
        concrete = {}
        for path, value in variant.values.items():
            try:
                concrete[path] = set_value(data, path, value)
            except PathError as err:
                where = variant.where[path]
                raise sweep.error(str(err), *(where[:-1] if where[0] == "grid" else where), key=True) from None
        instrument.add_sensors(sweep.spec.metrics, data)
        key = hashlib.sha256(f"{inputs}\n".encode() + json.dumps(data, sort_keys=True).encode()).hexdigest()
        variant.build_key = key[:16]
        variant.build = (out / BUILDS / variant.build_key).resolve()  # the runs start in folders of their own
        if not buildcache.up_to_date(variant.build, key):
            _build(sweep, variant, data, smap, cat, concrete)
            buildcache.record(variant.build, key)
    tasks = [RunTask(run=f"{v.id}-s{seed}", variant=v.id, seed=seed, values=v.values, build_key=v.build_key,
                     build_dir=str(v.build), duration=sweep.spec.duration, timeout=sweep.spec.timeout,
                     client=sweep.spec.client, client_cwd=str(sweep.folder),
                     metrics=[m.model_dump() for m in sweep.spec.metrics])
             for v in variants for seed in sweep.spec.seeds]
    return variants, tasks


def _build(sweep: Sweep, variant: Variant, data: dict, smap, cat, concrete: dict[str, tuple]) -> None:
    from morsec.compiler.build import compile_scene, write_build
    from morsec.scene.validate import validate_scene
    try:
        files = compile_scene(validate_scene(copy.deepcopy(data), smap, cat), cat)
    except SceneError as err:
        from morsec.frontends.load import load_scene
        load_scene(sweep.scene, cat)  # the scene's own mistake: reported at its place in the scene file
        raise _located(sweep, variant, err, concrete) from None
    assert variant.build is not None
    write_build(files, variant.build)


def _located(sweep: Sweep, variant: Variant, err: SceneError, concrete: dict[str, tuple]) -> MorsecError:
    """The scene's error at the sweep's value that caused it (the one whose path the message names), else at
    the variant's first value."""
    message = err.message
    best = None
    for path, parts in concrete.items():
        written = yaml_path(parts)
        if message == written or message.startswith((written + ":", written + ".", written + "[")):
            if best is None or len(written) > len(yaml_path(concrete[best])):
                best = path
    if best is None:
        best = next(iter(variant.values), None)
    if best is None:  # the metrics' sensors
        return sweep.error(f"the scene with the metrics' sensors is invalid: {message}", "metrics")
    shown = json.dumps(variant.values[best])
    return sweep.error(f"{shown} makes the scene invalid: {message}", *variant.where[best])
