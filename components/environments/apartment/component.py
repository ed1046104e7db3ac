from morsec.component import Environment
from morsec.kits.layout import block, rgba

WALL = rgba(1.0, 1.0, 1.0)
WOOD = rgba(0.853, 0.737, 0.451)
DARK_WOOD = rgba(0.2, 0.15, 0.08)
RED_FABRIC = rgba(0.387, 0.05, 0.07)
DESK = rgba(0.92, 0.72, 0.353)

# MORSE's apartment walls (its C6_plein_ext_P mesh, 2.5 m high, ~0.1 m thick): one box per wall, window sill
# (up to 1 m; the window above it, open, up to 2.1 m) and lintel (above a door or a window, from 2.1 m)
WALLS = (
        ((-5.75, -2.12, 0.0), (-5.66, -1.12, 2.5)),  # wall
        ((-5.75, -1.12, 0.0), (-5.66, 0.95, 1.0)),  # sill
        ((-5.75, -1.12, 2.1), (-5.66, 0.95, 2.5)),  # lintel
        ((-5.75, 0.94, 0.0), (-5.66, 2.94, 2.5)),  # wall
        ((-5.75, 2.94, 0.0), (-5.66, 5.01, 1.0)),  # sill
        ((-5.75, 2.94, 2.1), (-5.66, 5.01, 2.5)),  # lintel
        ((-5.75, 5.01, 0.0), (-5.66, 6.01, 2.5)),  # wall
        ((-1.69, 0.91, 0.0), (-1.58, 1.98, 2.5)),  # wall
        ((-1.69, 1.98, 2.1), (-1.58, 3.07, 2.5)),  # lintel
        ((-1.69, 3.06, 0.0), (-1.58, 4.01, 2.5)),  # wall
        ((-1.69, 4.0, 0.0), (-1.58, 5.04, 1.0)),  # sill
        ((-1.69, 4.0, 2.1), (-1.58, 5.04, 2.5)),  # lintel
        ((-1.69, 5.01, 0.0), (-1.58, 6.01, 2.5)),  # wall
        ((1.37, 1.98, 0.0), (1.47, 2.98, 2.5)),  # wall
        ((1.37, 2.97, 0.0), (1.47, 5.04, 1.0)),  # sill
        ((1.37, 2.97, 2.1), (1.47, 5.04, 2.5)),  # lintel
        ((1.37, 5.04, 0.0), (1.47, 6.08, 2.5)),  # wall
        ((-5.7, -2.21, 0.0), (-4.7, -2.11, 2.5)),  # wall
        ((-5.7, 1.89, 0.0), (-4.7, 1.99, 2.5)),  # wall
        ((-4.71, 1.89, 0.0), (-3.67, 1.99, 1.0)),  # sill
        ((-4.71, 1.89, 2.1), (-3.67, 1.99, 2.5)),  # lintel
        ((-3.67, 1.89, 0.0), (-2.73, 1.99, 2.5)),  # wall
        ((-2.73, 1.89, 2.1), (-0.55, 1.99, 2.5)),  # lintel
        ((-0.55, 1.89, 0.0), (1.42, 1.99, 2.5)),  # wall
        ((-5.7, 6.0, 0.0), (-4.7, 6.09, 2.5)),  # wall
        ((-4.71, 6.0, 0.0), (-2.64, 6.09, 1.0)),  # sill
        ((-4.71, 6.0, 2.1), (-2.64, 6.09, 2.5)),  # lintel
        ((-2.64, 6.0, 0.0), (-1.64, 6.09, 2.5)),  # wall
        ((-1.64, 6.0, 0.0), (-0.55, 6.09, 1.0)),  # sill
        ((-1.64, 6.0, 2.1), (-0.55, 6.09, 2.5)),  # lintel
        ((-0.55, 6.0, 0.0), (0.34, 6.09, 2.5)),  # wall
        ((0.34, 6.0, 2.1), (1.43, 6.09, 2.5)),  # lintel
)


class Apartment(Environment):
    """MORSE's apartment: a flat of three rooms on a 21.8 m square floor (x and y within ±10.9 m, top at
    z = 0): a bedroom and a kitchen-dining room along its north wall (y = 6.04), a living room with a sofa,
    armchairs, a carpet and a low table, 2.5 m walls with windows (sills 1 m high, open up to 2.1 m) and
    doorways, and an office corner to the south-east (four desks, two drawer blocks) open to the rest of
    the floor. IKEA furniture and desks are static boxes the size of MORSE's (named as in apartment.blend);
    MORSE's file tags no object: scripts add their own (PassiveObject, setgraspable)."""

    short_descr = "MORSE's apartment: bedroom, kitchen, living room, office corner, IKEA furniture"
    bounds = ((-10.9, -10.9, 0.0), (10.9, 10.9, 2.5))
    layout = (
        *(block(f"wall_{i:02d}", lo, hi, WALL) for i, (lo, hi) in enumerate(WALLS)),
        block("IKEA_Plant_1", (-5.26, -2.01, 0.0), (-4.61, -1.39, 1.66), rgba(0.54, 0.80, 0.19)),
        block("IKEA_Plant_2", (0.33, 2.27, 0.0), (1.33, 3.01, 1.05), rgba(0.54, 0.80, 0.19)),
        block("IKEA_RUTBO", (-1.44, 5.56, 0.46), (-1.14, 5.82, 1.60), rgba(0.99, 0.97, 0.84)),
        block("IKEA_armchair_EKTORP", (-4.93, 0.49, 0.0), (-3.91, 1.46, 0.77), RED_FABRIC),
        block("IKEA_armchair_EKTORP.001", (-3.43, -1.87, 0.0), (-2.42, -0.91, 0.77), RED_FABRIC),
        block("IKEA_bed_FJELLSE", (-5.62, 3.60, 0.0), (-3.55, 4.61, 0.80), rgba(0.92, 0.72, 0.35)),
        block("IKEA_carpet_DRAGOR", (-5.45, -1.90, 0.0), (-1.97, 1.67, 0.01), rgba(0.80, 0.68, 0.46)),
        block("IKEA_chair_PELLO", (-0.52, 4.93, 0.0), (0.37, 5.94, 0.96), WOOD),
        block("IKEA_chair_PELLO.001", (-1.52, 4.33, 0.0), (-0.56, 5.14, 0.96), WOOD),
        block("IKEA_chair_STEFAN", (0.64, 4.47, 0.0), (1.06, 4.96, 0.90), DARK_WOOD),
        block("IKEA_chair_STEFAN.001", (-0.06, 3.44, 0.0), (0.56, 4.02, 0.90), DARK_WOOD),
        block("IKEA_chest_HEMNES", (-2.21, 3.51, 0.0), (-1.69, 4.61, 0.97), rgba(0.39, 0.17, 0.10)),
        block("IKEA_console_HEMNES", (-4.26, 5.59, 0.0), (-2.67, 5.99, 0.74), DARK_WOOD),
        block("IKEA_cupboard_BILLY_1", (-5.64, 2.00, 0.0), (-4.84, 2.28, 2.02), WOOD),
        block("IKEA_cupboard_BILLY_2", (-1.59, 3.75, 0.0), (-1.28, 4.15, 1.06), WOOD),
        block("IKEA_cupboard_BILLY_3", (-1.59, 2.93, 0.0), (-1.27, 3.73, 1.06), WOOD),
        block("IKEA_lamp_orgel", (-3.95, -1.86, 0.0), (-3.71, -1.61, 1.54), rgba(0.95, 0.95, 0.9)),
        block("IKEA_low_table_LACK_1", (-1.55, 5.42, 0.0), (-1.00, 5.97, 0.45), DARK_WOOD),
        block("IKEA_low_table_LACK_1.001", (-5.42, 4.63, 0.0), (-4.87, 5.18, 0.45), DARK_WOOD),
        block("IKEA_low_table_LACK_2", (-4.24, -0.63, 0.0), (-3.25, 0.41, 0.45), DARK_WOOD),
        block("IKEA_sofa_EKTORP", (-5.57, -1.86, 0.0), (-3.74, 0.07, 0.95), RED_FABRIC),
        block("IKEA_table_TORSBY", (0.51, 3.21, 0.0), (1.36, 4.56, 0.75), DARK_WOOD),
        block("IKEAShelf", (-4.86, -3.76, 0.0), (-3.67, -2.57, 0.79), rgba(0.478, 0.34, 0.094)),
        block("office_desk", (-0.57, -3.14, 0.0), (1.03, -2.34, 0.76), DESK),
        block("office_desk.001", (1.06, -3.13, 0.0), (2.66, -2.33, 0.76), DESK),
        block("office_desk.002", (1.86, -2.32, 0.0), (2.67, -0.72, 0.76), DESK),
        block("office_desk.003", (1.87, -0.71, 0.0), (2.67, 0.89, 0.76), DESK),
        block("office_drawer_block", (1.96, 0.11, 0.0), (2.57, 0.54, 0.56), DESK),
        block("office_drawer_block.001", (-0.41, -3.05, 0.0), (0.02, -2.44, 0.56), DESK),
    )


COMPONENT = Apartment
