"""MORSE's `morse.helpers.transformation.Transformation3d`: a frame in the world (a component's `position_3d`, its
robot's `robot_parent.position_3d`), or between two frames (`transformation3d_with`).

The pose is kept in double precision, from MuJoCo's, and the numbers (`x`, `yaw`, `distance` ...) are computed
from it: a MORSE component reads what morsec's own components read. `matrix`, `rotation`, `rotation_matrix`,
`translation` and `euler` are Blender's types (`morse.core.mathutils`, single precision, `*` as in Blender 2.7x);
assigning `matrix` or `euler` sets the pose. Euler angles are Blender's (`to_euler` of the matrix).
"""

from __future__ import annotations

import math

from morse.core import mathutils
from morsec.kits.geometry import euler_of_xmat, times_transpose, transpose_apply, transpose_times

__all__ = ["Transformation3d"]

_IDENTITY = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)


def _euler_matrix(roll: float, pitch: float, yaw: float) -> tuple:
    cr, sr, cp, sp, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw), \
        math.sin(yaw)
    return (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
            sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
            -sp, cp * sr, cp * cr)


class Transformation3d:
    """The transformation from the world (or another frame) to a frame: a rotation and a translation."""

    def __init__(self, obj):
        self._p: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self._r: tuple = _IDENTITY
        self._e: tuple[float, float, float] | None = (0.0, 0.0, 0.0)  # (roll, pitch, yaw), computed on demand
        if obj is not None:
            self.update(obj)

    def _set(self, p, r) -> None:
        self._p, self._r, self._e = tuple(float(v) for v in p), tuple(float(v) for v in r), None

    def _angles(self) -> tuple[float, float, float]:
        if self._e is None:
            self._e = euler_of_xmat(self._r)
        return self._e

    # ---- numbers, in double precision
    @property
    def x(self) -> float:
        return self._p[0]

    @property
    def y(self) -> float:
        return self._p[1]

    @property
    def z(self) -> float:
        return self._p[2]

    @property
    def roll(self) -> float:
        return self._angles()[0]

    @property
    def pitch(self) -> float:
        return self._angles()[1]

    @property
    def yaw(self) -> float:
        return self._angles()[2]

    # ---- Blender's types
    @property
    def matrix(self) -> mathutils.Matrix:
        r, p = self._r, self._p
        return mathutils.Matrix(((r[0], r[1], r[2], p[0]), (r[3], r[4], r[5], p[1]), (r[6], r[7], r[8], p[2]),
                                 (0.0, 0.0, 0.0, 1.0)))

    @matrix.setter
    def matrix(self, value) -> None:
        rows = [list(row) for row in value]
        self._set((rows[0][3], rows[1][3], rows[2][3]), [rows[i][j] for i in range(3) for j in range(3)])

    @property
    def euler(self) -> mathutils.Euler:
        return mathutils.Euler(self._angles())

    @euler.setter
    def euler(self, value) -> None:
        roll, pitch, yaw = (float(v) for v in value)
        self._r, self._e = _euler_matrix(roll, pitch, yaw), (roll, pitch, yaw)

    @property
    def rotation(self) -> mathutils.Quaternion:
        """The rotation as a unit quaternion."""
        return self.rotation_matrix.to_quaternion()

    @property
    def rotation_matrix(self) -> mathutils.Matrix:
        r = self._r
        return mathutils.Matrix(((r[0], r[1], r[2]), (r[3], r[4], r[5]), (r[6], r[7], r[8])))

    @property
    def translation(self) -> mathutils.Vector:
        return mathutils.Vector(self._p)

    # ---- between frames
    def transformation3d_with(self, t3d: Transformation3d) -> Transformation3d:
        """inv(self) * t3d: `t3d`'s frame seen from this one."""
        res = Transformation3d(None)
        p, q = self._p, t3d._p
        res._set(transpose_apply(self._r, (q[0] - p[0], q[1] - p[1], q[2] - p[2])), transpose_times(self._r, t3d._r))
        return res

    def distance(self, t3d: Transformation3d) -> float:
        return math.dist(self._p, t3d._p)

    def distance_2d(self, t3d: Transformation3d) -> float:
        return math.dist(self._p[:2], t3d._p[:2])

    def update(self, obj) -> None:
        """This transformation becomes `obj`'s place in the world (a game object)."""
        pose = getattr(obj, "_morsec_pose", None)
        if pose is not None:  # an emulated game object: MuJoCo's pose, in double precision
            self._set(*pose())
            return
        rot = obj.worldOrientation
        self._set(obj.worldPosition, [rot[i][j] for i in range(3) for j in range(3)])

    def update_Y_forward(self, obj) -> None:
        """As update, for the robots of Blender's vehicle wrapper that go forward along y (their frame turned
        by -pi/2 about z)."""
        self.update(obj)
        self._set(self._p, times_transpose(self._r, (0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0)))

    def __str__(self) -> str:
        return f"x : {self.x} y : {self.y} z : {self.z} yaw : {self.yaw} pitch : {self.pitch} roll : {self.roll}"
