"""The sweep file: a scene, how long each run lasts, the seeds, what varies (a grid of scene paths and their
values, and/or a list of variants), how a run is judged (a client command, metrics morsec computes). YAML or
TOML, validated by pydantic models; every mistake is one line at the file's line and column, as a scene's."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

from pydantic import BeforeValidator, Field, ValidationError, field_validator

from morsec.errors import MorsecError, yaml_path
from morsec.frontends.text import read_data_file
from morsec.scene.models import Name, Positive, Strict
from morsec.scene.sourcemap import SourceMap
from morsec.scene.validate import scene_error

SWEEP_MAPPING = "a sweep must be a mapping with scene, duration, seeds, grid or variants, client and metrics"
DEFAULT_TIMEOUT = 600.0  # wall-clock s a run may take, start to end, before it is stopped (timed_out)
MAX_RUNS = 100_000


def _seed_count(value: Any) -> Any:
    """`seeds: 10` is seeds 0 to 9."""
    if isinstance(value, int) and not isinstance(value, bool):
        if value < 1:
            raise ValueError("a number of seeds must be 1 or more")
        return list(range(value))
    return value


Seed = Annotated[int, Field(ge=0)]


class MetricSpec(Strict):
    """What morsec measures of one robot, from its streams: final pose, distance travelled, contacts begun, and
    the simulated time it first enters each zone."""

    robot: Name = Field(description="the robot's name")
    pose: Name | None = Field(None, description="a pose sensor of the robot to read, its noise included (default: "
                              "a pose sensor morsec adds at the robot's origin, without noise)")
    zones: list[Name] = Field(default_factory=list, description="zones (by name, or type when unnamed) whose first "
                              "entry time is measured")


class SweepSpec(Strict):
    scene: str = Field(description="the scene (YAML or TOML), relative to the sweep file")
    duration: Positive = Field(description="simulated seconds of each run (the most it lasts, with a client)")
    seeds: Annotated[list[Seed], BeforeValidator(_seed_count), Field(min_length=1)] = Field(
        default_factory=lambda: [0], description="noise seeds, each run of every variant: a list, or a count N "
        "(0 to N-1)")
    grid: dict[str, Annotated[list[Any], Field(min_length=1)]] = Field(
        default_factory=dict, description="scene path: its values; every combination is a variant")
    variants: list[dict[str, Any]] = Field(
        default_factory=list, description="explicit variants, each {scene path: value}; crossed with the grid")
    client: str | None = Field(None, description="shell command run against each run, in the sweep file's folder, "
                               "its ports in the environment; may print a JSON object of metrics as its last line")
    metrics: list[MetricSpec] = Field(default_factory=list, description="what morsec measures of which robots")
    timeout: Positive = Field(DEFAULT_TIMEOUT, description="wall-clock seconds a run may take before it is stopped")

    @field_validator("seeds")
    @classmethod
    def _distinct_seeds(cls, seeds: list[int]) -> list[int]:
        twice = sorted({s for s in seeds if seeds.count(s) > 1})
        if twice:
            raise ValueError(f"seed {twice[0]} is listed twice")
        return seeds

    @field_validator("client")
    @classmethod
    def _command(cls, command: str | None) -> str | None:
        if command is not None and not command.strip():
            raise ValueError("the client command is empty")
        return command


@dataclass
class Sweep:
    path: Path
    spec: SweepSpec
    smap: SourceMap

    @property
    def folder(self) -> Path:
        return self.path.resolve().parent

    @property
    def scene(self) -> Path:
        return (self.folder / self.spec.scene).resolve()

    def error(self, message: str, *where: Any, key: bool = False) -> MorsecError:
        """A MorsecError at the position of `where` (a path in the sweep file) with its YAML path."""
        pos = self.smap.find(where, key=key)
        line, col = pos if pos else (None, None)
        label = yaml_path(where)
        return MorsecError(f"{label}: {message}" if label else message, str(self.path), line, col)


def load_sweep(path: Path) -> Sweep:
    """The validated sweep file; MorsecError (file:line:col) otherwise."""
    path = Path(path)
    data, smap = read_data_file(path, "sweep", SWEEP_MAPPING)
    try:
        spec = SweepSpec.model_validate(data)
    except ValidationError as err:
        raise scene_error(err, data, smap) from None
    return Sweep(path, spec, smap)
