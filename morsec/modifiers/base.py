"""What a modifier is: validated parameters (keyword -> environment property -> default) and `modify`."""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np
from pydantic import BaseModel, ConfigDict


class ModifierParams(BaseModel):
    # built on first use: a run builds the validators of the modifiers its scene uses only
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, defer_build=True)


class Modifier:
    Params: ClassVar[type[ModifierParams]] = ModifierParams
    # environment property read when a parameter is not given: {param: env property}
    env_defaults: ClassVar[dict[str, str]] = {}
    needs_geo: ClassVar[bool] = False  # needs the environment's longitude, latitude and altitude
    # True: what modify() does to a tick's data follows from that data and what draw() takes at that tick
    # alone (modify(data) is apply(data, draw())), and it writes only fields the sensor computes: on a
    # SampledSensor it draws at the tick and applies when the data is read (SampledSensor.apply_modifiers).
    # False (a modifier with state, e.g. one that integrates): it runs at the tick, which computes the data
    deferrable: ClassVar[bool] = False

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        # a subclass that writes its own modify() but not apply() (a component's own noise, from PoseNoise) runs
        # at the tick: deferred, only apply() would run, and its modify() never
        if "modify" in cls.__dict__ and "apply" not in cls.__dict__ and "deferrable" not in cls.__dict__:
            cls.deferrable = False

    def __init__(self, params: ModifierParams, rng: np.random.Generator, sim: Any = None):
        self.params = params
        self.rng = rng
        self.sim = sim

    @classmethod
    def resolve_params(cls, given: dict, env_properties: dict) -> ModifierParams:
        values = dict(given)
        for param, prop in cls.env_defaults.items():
            if param not in values and prop in env_properties:
                values[param] = env_properties[prop]
        return cls.Params.model_validate(values)

    def modify(self, data: dict) -> None:
        raise NotImplementedError

    def draw(self) -> Any:
        """A deferrable modifier: what it takes at a tick (its noise), for apply()."""
        raise NotImplementedError

    def apply(self, data: dict, drawn: Any) -> None:
        """A deferrable modifier: change the tick's data with what draw() took at that tick."""
        raise NotImplementedError
