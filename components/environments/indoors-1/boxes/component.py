from morsec.component import Environment


def _box(name: str, x: float, y: float, color: list[float]) -> dict:
    # MORSE's boxes.blend: a 1 m cube scaled to 1.8 m high, of its material's colour, with the game property
    # Object = its name (what the semantic camera tracks, and reports under that name); at rest, as MORSE's
    # dynamic boxes were, its top 1.865 m above the floor (MORSE's radar altimeter test: 13.14 m from 15 m)
    return {"name": name, "type": "box", "translate": [x, y, 0.965], "size": [1.0, 1.0, 1.8], "color": color,
            "properties": {"Object": name}}


class IndoorsBoxes(Environment):
    """A 30 m x 20 m hall centred on the origin: floor at z = 0, four 2.5 m walls (inner faces at
    x = ±15 m and y = ±10 m, 0.2 m thick), no ceiling. MORSE's `indoors-1/boxes`: its three named boxes,
    RedBox, BlueBox and GreenBox, are passive objects tagged `Object` (the semantic camera sees them),
    and three more static boxes stand in the other quadrants."""

    short_descr = "Room with walls and boxes"
    objects = (
        _box("RedBox", -7.5, 0.0, [0.952, 0.115, 0.049]),
        _box("BlueBox", -3.5, -3.0, [0.0, 0.346, 0.952]),
        _box("GreenBox", -6.5, 6.0, [0.0, 0.952, 0.019]),
    )


COMPONENT = IndoorsBoxes
