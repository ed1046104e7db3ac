"""The plain-float matrix helpers of kits.geometry (sensors and the ground robots' tick use them every frame)
against numpy's products."""

from __future__ import annotations

import numpy as np
import pytest

from morsec.kits.geometry import euler_to_quat, quat_to_matrix, times_transpose, transpose_apply, transpose_times


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
