"""kits.bounds: the checks a command's numbers pass before they reach MuJoCo's state."""

from __future__ import annotations

import numpy as np
import pytest

from morsec.kits.bounds import bounded_floats


def test_three_numbers_come_back_as_floats():
    assert bounded_floats([1, np.float32(2.5), "3"], 10.0, "a speed") == (1.0, 2.5, 3.0)
    assert all(type(v) is float for v in bounded_floats(np.arange(3), 10.0, "a speed"))


@pytest.mark.parametrize("values, message", [
    ([0.0, float("nan"), 0.0], "a speed must be finite and within ±10, got [ 0. nan  0.]"),
    ([0.0, 0.0, float("inf")], "a speed must be finite and within ±10, got [ 0.  0. inf]"),
    ([11.0, 0.0, 0.0], "a speed must be finite and within ±10, got [11.  0.  0.]"),
    ([1.0, 2.0], "a speed must be 3 numbers, got 2"),
    ([1.0, 2.0, 3.0, 4.0], "a speed must be 3 numbers, got 4"),
    ([1.0, "fast", 3.0], "could not convert string to float: 'fast'"),
])
def test_what_is_not_three_numbers_within_the_limit_is_a_value_error(values, message):
    with pytest.raises(ValueError) as err:
        bounded_floats(values, 10.0, "a speed")
    assert str(err.value) == message
