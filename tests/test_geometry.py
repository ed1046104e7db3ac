"""The plain-float matrix helpers of kits.geometry (sensors and the ground robots' tick use them every frame)
against numpy's products."""

from __future__ import annotations

import math

import numpy as np
import pytest

from morsec.kits.geometry import (
    euler_of_transpose_times,
    euler_of_xmat,
    euler_to_quat,
    quat_to_matrix,
    times_transpose,
    transpose_apply,
    transpose_times,
)
from morsec.runtime.trim import mean_velocity


def rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    return quat_to_matrix(euler_to_quat(roll, pitch, yaw))


@pytest.mark.parametrize("angles", [((0.1, -0.4, 2.0), (1.2, 0.3, -0.7)), ((0.0, 0.0, 0.0), (3.0, -1.5, 0.2))])
def test_products_of_row_major_lists_are_numpys(angles):
    a, b = rotation(*angles[0]), rotation(*angles[1])
    flat_a, flat_b = a.ravel().tolist(), b.ravel().tolist()
    assert transpose_times(flat_a, flat_b) == pytest.approx((a.T @ b).ravel().tolist(), abs=1e-12)
    assert times_transpose(flat_a, flat_b) == pytest.approx((a @ b.T).ravel().tolist(), abs=1e-12)
    v = [0.3, -2.0, 1.1]
    assert transpose_apply(flat_a, v) == pytest.approx((a.T @ v).tolist(), abs=1e-12)


def test_euler_of_a_relative_rotation_is_euler_of_xmat_of_the_product_to_the_bit():
    """Odometry's shortcut computes only the entries of Aᵀ B that euler_of_xmat reads: the same floats, in gimbal
    lock (pitch +-90 degrees), past 3 pi / 2 (the second triple) and anywhere else."""
    rng = np.random.default_rng(7)
    cases = [((0.0, 0.0, 0.0), (0.0, np.pi / 2, 0.3)), ((0.2, 0.0, 0.0), (0.2, -np.pi / 2, -1.0)),
             ((0.0, 0.0, 0.0), (3.0, 0.1, 3.0)), ((0.0, 0.0, 0.0), (0.0, np.pi, 0.0)),
             ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))]
    cases += [(tuple(rng.uniform(-np.pi, np.pi, 3)), tuple(rng.uniform(-np.pi, np.pi, 3))) for _ in range(500)]
    locked = second = 0
    for first_angles, second_angles in cases:
        a, b = rotation(*first_angles).ravel().tolist(), rotation(*second_angles).ravel().tolist()
        product = transpose_times(a, b)
        expected = euler_of_xmat(product)
        assert euler_of_transpose_times(a, b) == expected  # ==: the same floats, not approximately
        locked += np.hypot(product[0], product[3]) <= 16 * 1.1920929e-07
        second += abs(expected[1]) > np.pi / 2  # the second triple: pitch beyond +-90 degrees
    assert locked and second  # both rarer paths were taken


@pytest.mark.parametrize("heading", [True, False])
def test_a_robots_mean_velocity_written_out_is_the_matrix_products_to_the_bit(heading):
    """RobotHandle's trim reads a robot's mean velocity over a tick from its two poses with the rotation between
    them written out (it runs at every tick of every robot): the same sums in the same order as geometry's
    times_transpose / transpose_times, so the same bits."""
    rng = np.random.default_rng(7)
    for _ in range(500):
        rot0 = rotation(*rng.uniform(-np.pi, np.pi, 3)).reshape(-1).tolist()
        rot1 = rotation(*rng.uniform(-np.pi, np.pi, 3)).reshape(-1).tolist()
        pos0, pos1 = rng.normal(size=3).tolist(), rng.normal(size=3).tolist()
        dt = float(rng.uniform(0.001, 0.1))
        d00, d01, d02, d10, d11, d12, d20, d21, d22 = (times_transpose(rot1, rot0) if heading
                                                       else transpose_times(rot0, rot1))
        vx, vy, vz = (d21 - d12) / 2, (d02 - d20) / 2, (d10 - d01) / 2
        sin = math.sqrt(vx * vx + vy * vy + vz * vz)
        angle = math.atan2(sin, (d00 + d11 + d22 - 1.0) / 2.0)
        wz = vz * (angle / sin) if sin > 1e-12 else vz
        step = [b - a for a, b in zip(pos0, pos1)]
        start, end = transpose_apply(rot0, step), transpose_apply(rot1, step)
        expected = ((start[0] + end[0]) / 2.0 / dt, (start[1] + end[1]) / 2.0 / dt, wz / dt)
        assert mean_velocity(pos0, rot0, pos1, rot1, dt, heading) == expected
