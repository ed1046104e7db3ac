from morsec.component import Environment

FIRE_ORIGIN = (56.0, 0.0)  # where the fire starts
FIRE_SPACING = 1.2  # m between bushes, along +x
FIRE_PERIOD = 4.0  # s between two bushes catching fire
FIRE_BUSHES = 20


def _bush(k: int) -> dict:
    """The k-th bush of the fire line: it catches fire k * FIRE_PERIOD seconds after the start."""
    x = FIRE_ORIGIN[0] + FIRE_SPACING * k
    y = FIRE_ORIGIN[1] + (0.6 if k % 2 else -0.6) * (1 + k % 3) / 2
    return {"name": f"fire_{k:02d}", "type": "sphere", "translate": [x, y, 0.3], "size": [1.0, 1.0, 1.0],
            "color": [0.85, 0.3, 0.05], "properties": {"Fire": True, "Fire_Start": FIRE_PERIOD * k}}


class Rosace1(Environment):
    """The outdoor field of MORSE's ROSACE search-and-rescue scenario: flat grass at z = 0 around the origin,
    a few trees and farm buildings, low hills far away, and a fire spreading east from (56, 0): a line of
    20 bushes (passive objects tagged `Fire`) that catch fire one every 4 s, so that a thermometer near it
    reads hotter and hotter. MORSE's `land-1/rosace_1`."""

    short_descr = "Outdoor field with a spreading fire (ROSACE scenario)"
    objects = tuple(_bush(k) for k in range(FIRE_BUSHES))


COMPONENT = Rosace1
