"""`from morse.core import mathutils`: Blender's `mathutils` (the `mathutils` package, Blender's own code built as a
standalone module), as MORSE's components used it.

MORSE ran on Blender 2.7x, whose `*` multiplied matrices, vectors and quaternions (`rotation * vector`, `a * b`
composing rotations, `u * v` a dot product); Blender 2.8 and the `mathutils` package made that `@` and `*`
element-wise, so a MORSE component computing `rot * vec` would get a TypeError, and `mat_a * mat_b` a silently
wrong matrix. The classes here are the package's, subclassed so that `*` keeps Blender 2.7x's meaning (`@` works
too); every value the emulation hands a component (positions, orientations, `position_3d`) is one of them, and so
is whatever their methods return. A component importing Blender's `mathutils` itself gets the package as it is.
Values are Blender's single-precision floats, as in MORSE.
"""

from __future__ import annotations

from morsec.errors import MorsecError

try:
    import mathutils as _blender
except ImportError:
    raise MorsecError("MORSE-API components need Blender's mathutils: pip install 'morsec[morse-api]' (it builds "
                      "from source: a C compiler and Python's headers)") from None

__all__ = ["Color", "Euler", "Matrix", "Quaternion", "Vector", "geometry", "noise", "kdtree", "bvhtree"]

geometry = _blender.geometry
noise = getattr(_blender, "noise", None)
kdtree = getattr(_blender, "kdtree", None)
bvhtree = getattr(_blender, "bvhtree", None)
Color = _blender.Color


def ours(value):
    """A value of the package's types as one of this module's (tuples converted item by item)."""
    kind = _OURS.get(type(value))
    if kind is not None:
        return kind(value) if kind is not Euler else _euler(value, value.order)
    if isinstance(value, tuple):
        return tuple(ours(v) for v in value)
    return value


def _euler(angles, order: str = "XYZ"):
    """An Euler of ours. The package (3.3.0, built for Python 3.11) refuses every order given as a string,
    even Blender's default 'XYZ': Eulers are XYZ, as MORSE's components use them."""
    if order != "XYZ":
        from morse.core.emulation import not_emulated
        not_emulated(f"Euler order {order!r}", "the mathutils package refuses orders: Eulers are 'XYZ'")
    return Euler(tuple(angles))


def _returning_ours(name: str, method):
    def call(self, *args, **kwargs):
        if name == "to_euler" and args and isinstance(args[0], str):  # the order (see _euler)
            if args[0] != "XYZ":
                _euler((0, 0, 0), args[0])
            args = args[1:]
        return ours(method(self, *args, **kwargs))
    call.__name__ = call.__qualname__ = name
    call.__doc__ = method.__doc__
    return call


def _product(self, other):
    """Blender 2.7x's `*`: a matrix, vector or quaternion product between rotation types, a dot product between
    two vectors; a number scales, as before."""
    if isinstance(self, _blender.Vector) and isinstance(other, _blender.Vector):
        return self.dot(other)
    if isinstance(other, (_blender.Matrix, _blender.Vector, _blender.Quaternion)):
        return ours(_blender_matmul(self, other))
    return ours(_ELEMENTWISE[type(self).__mro__[1]](self, other))


def _blender_matmul(left, right):
    return left @ right


def _reflected(self, other):
    if isinstance(other, (int, float)):
        return ours(_ELEMENTWISE[type(self).__mro__[1]](self, other))
    return NotImplemented


def _adopt(cls):
    """Every method of the package's class that returns one of its values returns ours instead; `*` is 2.7x's."""
    base = cls.__mro__[1]
    for name, attr in vars(base).items():
        if name.startswith("__") or type(attr).__name__ != "method_descriptor":
            continue  # class methods (Matrix.Identity ...) already build the calling class
        setattr(cls, name, _returning_ours(name, attr))
    # not __getitem__: a matrix's row is a view that writes through (`matrix[0][3] = x`)
    for name in ("__add__", "__sub__", "__neg__", "__matmul__", "__truediv__", "__radd__", "__rsub__"):
        if hasattr(base, name):
            setattr(cls, name, _returning_ours(name, getattr(base, name)))
    if hasattr(base, "__mul__"):  # an Euler is not multiplied
        cls.__mul__ = _product
        cls.__rmul__ = _reflected
        cls.__imul__ = _product
    return cls


@_adopt
class Vector(_blender.Vector):
    __slots__ = ()


@_adopt
class Matrix(_blender.Matrix):
    __slots__ = ()


@_adopt
class Quaternion(_blender.Quaternion):
    __slots__ = ()


@_adopt
class Euler(_blender.Euler):
    __slots__ = ()

    def __new__(cls, angles=(0.0, 0.0, 0.0), order="XYZ"):
        if order != "XYZ":
            _euler(angles, order)
        return super().__new__(cls, tuple(angles))


_OURS = {_blender.Vector: Vector, _blender.Matrix: Matrix, _blender.Quaternion: Quaternion, _blender.Euler: Euler}
_ELEMENTWISE = {base: base.__mul__ for base in _OURS if hasattr(base, "__mul__")}
