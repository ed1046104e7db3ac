"""Gaussian noise, no bias (MORSE's Noise / PoseNoise / IMUNoise / odometry noise)."""

from __future__ import annotations

import math

import numpy as np
from pydantic import ConfigDict, Field

from morsec.kits.geometry import normalize_angle
from morsec.modifiers.base import Modifier, ModifierParams

Std = float | dict[str, float]


def _std(value: Std, axis: str) -> float:
    return float(value.get(axis, 0.0)) if isinstance(value, dict) else float(value)


class PoseNoiseParams(ModifierParams):
    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, populate_by_name=True)
    pos_std: Std = Field(0.05, description="m; a number or {x, y, z}")
    rot_std: Std = Field(math.radians(5), description="rad; a number or {roll, pitch, yaw}")
    planar: bool = Field(False, alias="_2D", description="_2D: only x, y and yaw")


BATCH = 512  # ticks of noise drawn at once: one numpy call per 512 ticks instead of one per tick


class GaussianNoise(Modifier):
    """Draws zero-mean Gaussian noise for a fixed list of standard deviations, a row per tick (the draws
    come in batches, from the modifier's own seeded stream: same seed, same noise). Deferrable: a row is
    drawn at every tick, whether or not the data is read, so the noise a tick gets never depends on reads."""

    deferrable = True
    stds: list[float] = []
    _rows: list[list[float]] | None = None  # the batch's rows not drawn yet, the next one last

    def draw(self) -> list[float]:
        rows = self._rows
        if not rows:
            rows = self._rows = self.rng.normal(0.0, self.stds, size=(BATCH, len(self.stds))).tolist()
            rows.reverse()
        return rows.pop()

    def modify(self, data: dict) -> None:
        self.apply(data, self.draw())


class PoseNoise(GaussianNoise):
    """x, y, z += N(0, pos_std); roll, pitch, yaw += N(0, rot_std) (with _2D: x, y, yaw only)."""

    Params = PoseNoiseParams
    positions = ("x", "y", "z")
    angles = ("roll", "pitch", "yaw")

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        p = self.params
        positions = tuple(a for a in self.positions if not (p.planar and a == "z"))
        angles = tuple(a for a in self.angles if not (p.planar and a != "yaw"))
        # one draw per tick for every noisy field: (field, std, is an angle)
        self.fields = [(a, _std(p.pos_std, a), False) for a in positions] + \
                      [(a, _std(p.rot_std, a), True) for a in angles]
        self.stds = [std for _, std, _ in self.fields]

    def apply(self, data: dict, drawn: list[float]) -> None:
        for (field, _, angle), n in zip(self.fields, drawn):
            if field in data:
                value = float(data[field]) + n
                data[field] = normalize_angle(value) if angle else value


class PositionNoise(PoseNoise):
    """x, y, z += N(0, pos_std) (GPS)."""

    angles = ()


class OrientationNoise(PoseNoise):
    """roll, pitch, yaw += N(0, rot_std) (gyroscope)."""

    positions = ()


class IMUNoiseParams(ModifierParams):
    gyro_std: Std = Field(0.5, description="rad/s; a number or {x, y, z}")
    accel_std: Std = Field(0.5, description="m/s^2; a number or {x, y, z}")


class IMUNoise(GaussianNoise):
    """angular_velocity += N(0, gyro_std), linear_acceleration += N(0, accel_std), per axis."""

    Params = IMUNoiseParams

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        p = self.params
        self.stds = [_std(p.gyro_std, a) for a in "xyz"] + [_std(p.accel_std, a) for a in "xyz"]

    def apply(self, data: dict, drawn: list[float]) -> None:
        n0, n1, n2, n3, n4, n5 = drawn  # written out
        if "angular_velocity" in data:
            x, y, z = data["angular_velocity"]
            data["angular_velocity"] = [float(x) + n0, float(y) + n1, float(z) + n2]
        if "linear_acceleration" in data:
            x, y, z = data["linear_acceleration"]
            data["linear_acceleration"] = [float(x) + n3, float(y) + n4, float(z) + n5]


class OdometryNoiseParams(ModifierParams):
    factor: float = Field(1.05, description="scale error on travelled distances")
    factor_sigma: float = Field(0.0, ge=0)
    gyro_drift: float = Field(0.0, description="rad added to the heading each tick")
    gyro_drift_sigma: float = Field(0.0, ge=0)


class OdometryNoise(Modifier):
    """Odometry scale error and heading drift: deltas scaled and drifted; the integrated level is
    re-integrated from the noisy deltas."""

    Params = OdometryNoiseParams

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # the integrated odometry starts at 0 (the sensor's initial pose): so does its noisy twin, and the
        # first tick's motion is scaled and drifted like every other
        self.true_prev: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self.noisy = np.zeros(3)  # x, y, yaw

    def _factor(self) -> float:
        p = self.params
        return p.factor + (self.rng.normal(0.0, p.factor_sigma) if p.factor_sigma else 0.0)

    def _drift(self) -> float:
        p = self.params
        return p.gyro_drift + (self.rng.normal(0.0, p.gyro_drift_sigma) if p.gyro_drift_sigma else 0.0)

    def modify(self, data: dict) -> None:
        if "dS" in data:
            data["dS"] = float(data["dS"]) * self._factor()
        if "dx" in data:
            f = self._factor()
            for key in ("dx", "dy", "dz"):
                data[key] = float(data[key]) * f
            data["dyaw"] = normalize_angle(float(data["dyaw"]) + self._drift())
        if "x" in data and "yaw" in data:
            x, y, yaw = float(data["x"]), float(data["y"]), float(data["yaw"])
            px, py, pyaw = self.true_prev
            c, s = math.cos(pyaw), math.sin(pyaw)
            local = np.array([c * (x - px) + s * (y - py), -s * (x - px) + c * (y - py)]) * self._factor()
            dyaw = normalize_angle(yaw - pyaw) + self._drift()
            nyaw = self.noisy[2]
            self.noisy[0] += math.cos(nyaw) * local[0] - math.sin(nyaw) * local[1]
            self.noisy[1] += math.sin(nyaw) * local[0] + math.cos(nyaw) * local[1]
            self.noisy[2] = normalize_angle(nyaw + dyaw)
            self.true_prev = (x, y, yaw)
            data["x"], data["y"], data["yaw"] = (float(v) for v in self.noisy)
