from morsec.component import Environment
from morsec.kits.layout import block, rgba

WALL = rgba(0.671, 0.635, 0.635)  # MORSE's MatMurs


def _tagged(name: str, kind: str, lo, hi, color, mass: float, properties: dict) -> dict:
    """One of MORSE's tagged objects of indoor-1.blend (a rigid body of `mass` kg in MORSE), from its bounding box."""
    centre = [round((a + b) / 2, 3) for a, b in zip(lo, hi)]
    size = [round(b - a, 3) for a, b in zip(lo, hi)]
    if kind == "cylinder":
        size[0] = size[1] = min(size[0], size[1])
    return {"name": name, "type": kind, "translate": centre, "size": size, "color": color, "dynamic": True,
            "mass": mass, "properties": properties}


class IndoorsIndoor1(Environment):
    """MORSE's first tutorial's lab: a 39.2 x 30 m tiled floor (x within ±19.6 m, y within ±15 m, top at
    z = 0) closed by a wall on the west (x = -17.71) and one on the north (y = 14.05), 4.4 m high; desks,
    shelves, armchairs, a stool, a whiteboard and a rolling chair in its north-west quarter (static boxes
    the size of MORSE's furniture); and MORSE's five tagged objects, dynamic, with its names and game
    properties: RedBox, GreenBox, PinkBox, YellowBox (Object = 'Box') and Bottle1 (the last two on desks)."""

    short_descr = "MORSE's tutorial lab: floor, two walls, office furniture, five tagged boxes and a bottle"
    bounds = ((-19.6, -15.0, 0.0), (19.6, 15.0, 4.37))
    objects = (
        _tagged("RedBox", "box", (-1.97, 1.19, 0.01), (-0.97, 2.19, 1.01), [0.952, 0.115, 0.049], 5.0,
                {"Object": True}),
        _tagged("GreenBox", "box", (-12.16, 3.84, 0.0), (-11.66, 4.34, 0.5), [0.027, 0.755, 0.08], 4.0,
                {"Object": True}),
        _tagged("PinkBox", "box", (-1.27, 7.18, 0.99), (-0.57, 7.88, 1.49), [0.91, 0.175, 0.898], 3.0,
                {"Object": True, "Graspable": True}),
        _tagged("YellowBox", "box", (-5.96, 11.03, 1.41), (-5.11, 11.87, 2.25), [1.0, 1.0, 0.322], 5.0,
                {"Object": "Box"}),
        _tagged("Bottle1", "cylinder", (-7.67, 3.07, 0.93), (-7.47, 3.22, 1.43), [0.041, 0.588, 0.081], 1.0,
                {"Object": True, "Graspable": True}),
    )
    layout = (
        # MORSE's two wall planes (Plane, Plane.001), here 0.1 m thick on their outer side
        block("wall_west", (-17.81, -14.53, 0.0), (-17.71, 15.29, 4.37), WALL),
        block("wall_north", (-22.52, 14.05, 0.0), (22.43, 14.15, 4.34), WALL),
        # the furniture: each a box the size of MORSE's object (its bounding box), named as in indoor-1.blend
        block("Desk_1.001", (-7.58, 10.22, 0.0), (-4.60, 11.87, 1.35), rgba(0.46, 0.46, 0.46)),
        block("Desk_2.001", (-8.79, 2.47, 0.0), (-6.44, 3.71, 0.91), rgba(0.84, 0.85, 0.8)),
        block("Desk_3.000", (-12.96, 7.09, 0.0), (-10.31, 8.44, 0.96), rgba(0.88, 0.88, 0.88)),
        block("Desk_3.002", (-2.96, 7.09, 0.0), (-0.31, 8.44, 0.96), rgba(0.88, 0.88, 0.88)),
        block("Rolling_Chair.001", (-8.40, 0.77, 0.0), (-7.71, 1.68, 1.22), rgba(0.34, 0.34, 0.34)),
        block("Shelf_1.001", (-12.78, 10.87, 0.0), (-11.62, 11.74, 1.52), rgba(0.48, 0.34, 0.09)),
        block("Shelf_2.001", (-10.86, 12.76, 0.0), (-9.72, 13.44, 1.98), rgba(0.48, 0.34, 0.09)),
        block("Shelf_3.001", (-0.11, 10.65, 0.0), (1.06, 11.49, 1.18), rgba(0.75, 0.75, 0.75)),
        block("Stool", (-5.67, 9.27, 0.0), (-4.74, 10.20, 1.25), rgba(0.24, 0.24, 0.24)),
        block("red_heat.000", (-12.02, 5.72, 0.0), (-11.04, 6.47, 1.08), rgba(1.0, 0.339, 0.339)),
        block("red_heat.001", (-2.02, 5.72, 0.0), (-1.04, 6.47, 1.08), rgba(1.0, 0.339, 0.339)),
        block("whiteboard", (-3.51, 10.47, 0.0), (-1.59, 11.32, 2.01), rgba(0.95, 0.95, 0.95)),
    )


COMPONENT = IndoorsIndoor1
