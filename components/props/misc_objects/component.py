from morsec.component import Prop
from morsec.kits.layout import PropPart, prop_object

BLUE, BROWN, WINE = (0.269, 0.375, 0.927), (0.28, 0.152, 0.09), (0.46, 0.096, 0.031)


def _book(depth: float, height: float, thickness: float, color) -> dict:
    """A book standing on its bottom edge, its origin at its centre (as MORSE's)."""
    return prop_object((PropPart("body", (0.0, 0.0, 0.0), (thickness, depth, height)),), color)


class MiscObjects(Prop):
    """The objects of MORSE's props/misc_objects.blend, by their MORSE names: nine books (blue, brown and
    wine-red, fat, medium and thin) and a green bottle, each with MORSE's size and mass (dynamic: they fall
    and can be pushed or grasped) and MORSE's origin at the object's centre (`translate` z = half its height
    stands it on the floor). Their shape is their bounding box (the bottle: a cylinder). MORSE's file gives
    them no game property: `setgraspable()` or `properties:` tags them."""

    short_descr = "MORSE's props/misc_objects: nine books and a bottle"
    variants = {
        "Book_Blue_fat": _book(0.135, 0.2, 0.084, BLUE),
        "Book_Blue_medium": _book(0.135, 0.18, 0.05, BLUE),
        "Book_Blue_thin": _book(0.135, 0.2, 0.02, BLUE),
        "Book_Brown_fat": _book(0.135, 0.2, 0.084, BROWN),
        "Book_Brown_medium": _book(0.135, 0.19, 0.05, BROWN),
        "Book_Brown_thin": _book(0.135, 0.22, 0.02, BROWN),
        "Book_Wine_fat": _book(0.119, 0.167, 0.084, WINE),
        "Book_Wine_medium": _book(0.148, 0.2, 0.05, WINE),
        "Book_Wine_thin": _book(0.095, 0.151, 0.02, WINE),
        "Bottle": prop_object((PropPart("body", (0.0, 0.0, 0.0), (0.2, 0.2, 0.466), "cylinder"),),
                              (0.122, 0.473, 0.081), mass=1.12),
    }


COMPONENT = MiscObjects
