from morsec.component import Environment
from morsec.kits.layout import block, rgba, segment

WALL = rgba(0.753, 0.753, 0.753)
FURNITURE = rgba(0.8, 0.8, 0.8)
SHELF = rgba(0.307, 0.307, 0.307)
PATH = rgba(0.55, 0.5, 0.42)

# MORSE's SerpentsTrail, the path out of the room's east doorway: its centre line (x, y, z), read from the
# middle of its faces, as 1.5 m wide strips, then the platform it ends on
TRAIL = ((4.0, 0.0, 0.0), (11.3, 0.0, 0.0), (19.4, -3.7, -0.9), (20.0, -6.9, -0.9), (18.4, -10.1, 0.0),
         (14.1, -10.2, 0.0), (9.7, -10.9, 0.0), (8.3, -13.1, 0.6), (9.2, -17.2, 0.6), (12.2, -19.5, 0.0),
         (19.2, -16.5, 0.0), (21.0, -14.3, 0.0), (22.4, -12.4, 0.0), (24.7, -11.6, 0.0), (28.2, -11.6, 0.0))


def _labelled(name: str, lo, hi, properties: dict, color=FURNITURE) -> dict:
    """A door or drawer of MORSE's tutorial room, static, with the game properties the human's tutorial reads;
    named as in MORSE with '_' for '.' (a scene name cannot hold a '.')."""
    return {"name": name.replace(".", "_"), "type": "box", "translate": [round((a + b) / 2, 3) for a, b in zip(lo, hi)],
            "size": [round(max(b - a, 0.02), 3) for a, b in zip(lo, hi)], "color": color, "properties": properties}


class HumanTutTutorialScene(Environment):
    """The room of MORSE's human-avatar tutorial: an 8 x 12 m floor (x within ±4 m, y within ±6 m, top at
    z = 0) closed by 2.5 m walls with a 2 m doorway in the east wall (y from -1.03 to 1.04), a table with a
    cup (`CubeSelect`, Label 'Cup', Object, Graspable: what the human picks up), two chairs, a desk, a
    chest of drawers and a glass-door shelf whose doors and drawers carry MORSE's labels ('Drawer',
    'Right Door', 'Shelf Door', ...), and outside the doorway MORSE's winding trail down to a platform at
    x = 28..35.6 m, with nothing under it."""

    short_descr = "MORSE's human tutorial: a furnished room, labelled drawers and doors, a cup, a trail outside"
    bounds = ((-4.0, -20.6, -0.9), (35.6, 6.0, 2.5))
    objects = (
        # MORSE's cup overhangs the table's bounding box (y up to 2.37, the table's to 2.21): here 0.14 m further
        # onto the table, so that it stands on it
        {"name": "CubeSelect", "type": "cylinder", "translate": [-3.225, 2.125, 0.99], "size": [0.16, 0.16, 0.17],
         "color": [0.293, 0.293, 0.293], "dynamic": True, "mass": 1.0,
         "properties": {"Object": True, "Description": "Cup", "Label": "Cup", "Type": "", "Graspable": True}},
        _labelled("Drawers_Door.L", (-3.28, -3.92, 0.05), (-3.26, -3.25, 0.76),
                  {"Drawer": "Drawers_Door.L", "Open": False, "Description": "Left Sliding Door",
                   "Label": "Left Sliding Door"}),
        _labelled("Drawers_Door.M", (-3.29, -3.35, 0.05), (-3.27, -2.67, 0.76),
                  {"Drawer": "Drawers_Door.M", "Open": False, "Description": "Right Sliding Door",
                   "Label": "Right Sliding Door"}),
        _labelled("Drawers_Door.R", (-3.26, -2.64, 0.02), (-3.18, -1.95, 0.78),
                  {"Door": "right", "Open": False, "Description": "Right Door", "Label": "Right Door"}),
        *(_labelled(f"Drawers_Drawer{suffix}", (-3.87, -3.26, z0), (-3.2, -2.64, z1),
                    {"Drawer": f"Drawers_Drawer{suffix}", "Open": False, "Description": "Drawer", "Label": "Drawer"})
          for suffix, z0, z1 in (("", 1.02, 1.19), (".001", 1.19, 1.54), (".002", 1.55, 1.71),
                                 (".003", 1.72, 1.88), (".004", 1.89, 2.06))),
        *(_labelled(f"Shelf_{level}Door.{side}", (x0, -5.25, z0), (x0 + 0.59, -5.15, z1),
                    {"Door": "left" if side == "L" else "right", "Open": False, "Description": label,
                     "Label": label}, SHELF)
          for level, label, z0, z1 in (("Lower", "Lower Shelf Door", 0.08, 0.92), ("Upper", "Shelf Door", 0.94, 2.38))
          for side, x0 in (("L", 3.06), ("R", 2.46))),
    )
    layout = (
        # the walls (MORSE's Walls mesh, 1 cm thick, here 9 cm), the east one open from y = -1.03 to 1.04
        block("wall_west", (-4.05, -6.01, 0.0), (-3.96, 6.01, 2.5), WALL),
        block("wall_east_south", (3.96, -6.01, 0.0), (4.05, -1.03, 2.5), WALL),
        block("wall_east_north", (3.96, 1.04, 0.0), (4.05, 6.01, 2.5), WALL),
        block("wall_south", (-4.01, -6.05, 0.0), (4.01, -5.96, 2.5), WALL),
        block("wall_north", (-4.01, 5.96, 0.0), (4.01, 6.05, 2.5), WALL),
        block("Table", (-3.31, 1.21, 0.0), (-2.71, 2.21, 0.9), FURNITURE),
        block("Chair", (-2.66, 2.29, 0.0), (-2.05, 2.90, 0.96), FURNITURE),
        block("Chair2", (2.58, 1.80, 0.0), (3.24, 2.38, 0.77), rgba(0.969, 0.769, 0.408)),
        block("Desk_1", (1.85, 2.41, 0.0), (3.87, 3.53, 0.91), rgba(0.667, 0.667, 0.667)),
        block("Drawers", (-4.0, -4.0, 0.0), (-3.3, -1.83, 2.10), FURNITURE),
        block("Shelf", (2.42, -5.94, 0.0), (3.69, -5.27, 2.41), SHELF),
        block("Shelf2", (0.27, 5.24, 0.0), (1.27, 5.94, 2.0), FURNITURE),
        *(segment(f"SerpentsTrail_{i:02d}", a, b, 1.5, PATH) for i, (a, b) in enumerate(zip(TRAIL, TRAIL[1:]))),
        block("SerpentsTrail_platform", (28.2, -15.7, -0.2), (35.6, -8.2, 0.0), PATH),
    )


COMPONENT = HumanTutTutorialScene
