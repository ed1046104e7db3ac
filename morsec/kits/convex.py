"""A triangle mesh's collision shape as convex pieces. MuJoCo collides a mesh as its convex hull: a room's
walls in one mesh would collide as a solid block filling the room. Blender's game engine collided static
meshes triangle by triangle; this splits a mesh until each piece's hull stands for its triangles.

The triangles are split in two at the median of their centres along their longest extent until a piece is
* flat (every vertex within `tolerance` of one plane): a slab of `thickness` behind the faces (a floor, a wall),
* closed and convex (no vertex in front of any of its faces by more than `tolerance`; or none behind, for a
  mesh whose faces look inwards, as many do, unless it is larger than `room` across: a room seen from inside),
* open, convex either way and thin (a seat, a panel): its hull,
* or smaller than `min_size` across: its hull.
The result is a list of point sets, each a piece MuJoCo takes the hull of."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

THIN = 0.15  # an open convex piece is kept whole when its smallest extent is below this share of its largest
CHECKED_POINTS = 512  # the convexity test checks this many of a piece's vertices at most


@dataclass
class Piece:
    points: np.ndarray  # (n, 3): the piece is their convex hull
    volume: float  # an estimate (its box along its principal axes), to share a mass among pieces


def convex_pieces(vertices: np.ndarray, triangles: np.ndarray, tolerance: float = 0.02, min_size: float = 0.1,
                  thickness: float = 0.02, room: float = 2.0, max_pieces: int = 256) -> list[Piece]:
    vertices = np.asarray(vertices, float)
    welded, triangles = _weld(vertices, np.asarray(triangles, np.int64))
    a, b, c = (welded[triangles[:, i]] for i in range(3))
    cross = np.cross(b - a, c - a)
    area2 = np.linalg.norm(cross, axis=1)
    keep = area2 > 1e-12
    triangles, cross, area2 = triangles[keep], cross[keep], area2[keep]
    if not len(triangles):
        return []
    normals = cross / area2[:, None]
    offsets = np.einsum("ij,ij->i", normals, welded[triangles[:, 0]])
    centres = welded[triangles].mean(axis=1)
    pieces: list[Piece] = []
    work = _components(triangles)
    while work:
        tris = work.pop()
        points = welded[np.unique(triangles[tris])]
        if len(tris) == 1 or len(pieces) + len(work) >= max_pieces or _extent(points).max() < min_size \
                or _flat(points, tolerance):
            accept = True
        else:
            outwards = _convex(points, normals[tris], offsets[tris], tolerance)
            inwards = _convex(points, -normals[tris], -offsets[tris], tolerance)
            if _closed(triangles[tris]):
                accept = outwards or (inwards and _extent(points)[0] < room)
            else:
                accept = (outwards or inwards) and _thin(points)
        if accept:
            pieces.append(_solid(points, normals[tris], area2[tris], thickness))
        else:
            work.extend(_split(tris, centres))
    return pieces


def _weld(vertices: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vertices at the same place made one (Blender splits them along seams), so that edges can be matched."""
    keys = np.round(vertices / 1e-6).astype(np.int64)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return vertices[first], inverse.reshape(-1)[triangles]


def hull_piece(points: np.ndarray, thickness: float = 0.02) -> Piece:
    """All the points as one piece (Blender's Convex Hull bounds), thickened if they are flat."""
    points = np.asarray(points, float)
    return _solid(points, np.zeros((1, 3)), np.ones(1), thickness)


def _components(triangles: np.ndarray) -> list[np.ndarray]:
    """The triangles of each connected part (parts share no vertex), as index arrays."""
    parent = np.arange(triangles.max() + 1)

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b, c in triangles.tolist():
        ra, rb, rc = root(a), root(b), root(c)
        parent[rb] = ra
        parent[rc] = ra
    roots = np.array([root(a) for a in triangles[:, 0].tolist()])
    return [np.flatnonzero(roots == r) for r in np.unique(roots)]


def _extent(points: np.ndarray) -> np.ndarray:
    """The piece's extents along its principal axes, largest first."""
    return _principal(points)[0]


def _flat(points: np.ndarray, tolerance: float) -> bool:
    return bool(_extent(points)[2] <= tolerance)


def _thin(points: np.ndarray) -> bool:
    extent = _extent(points)
    return bool(extent[2] <= THIN * extent[0])


def _convex(points: np.ndarray, normals: np.ndarray, offsets: np.ndarray, tolerance: float) -> bool:
    """No vertex in front of any face (along its normal) by more than `tolerance`."""
    if len(points) > CHECKED_POINTS:
        points = points[np.linspace(0, len(points) - 1, CHECKED_POINTS).astype(int)]
    for start in range(0, len(normals), 2048):
        ahead = normals[start:start + 2048] @ points.T - offsets[start:start + 2048, None]
        if ahead.max() > tolerance:
            return False
    return True


def _closed(triangles: np.ndarray) -> bool:
    """Every edge is shared by exactly two triangles."""
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return bool(np.all(counts == 2))


def _split(tris: np.ndarray, centres: np.ndarray) -> list[np.ndarray]:
    c = centres[tris]
    axis = int(np.argmax(c.max(axis=0) - c.min(axis=0)))
    order = np.argsort(c[:, axis], kind="stable")
    half = len(order) // 2
    return [tris[order[:half]], tris[order[half:]]]


def _solid(points: np.ndarray, normals: np.ndarray, area2: np.ndarray, thickness: float) -> Piece:
    """The piece's points, given a thickness behind its faces when they are (nearly) flat, and across a line
    when they are (nearly) on one: a hull needs a volume."""
    normal = (normals * area2[:, None]).sum(axis=0)
    length = np.linalg.norm(normal)
    for _ in range(2):
        extent, axes = _principal(points)
        if extent[2] >= thickness / 2:
            break
        if length > 1e-9 * area2.sum():  # behind the faces
            points = np.concatenate([points, points - normal / length * thickness])
            length = 0.0
        else:  # faces both ways, or a line: as thick on each side
            points = np.concatenate([points + axes[2] * thickness / 2, points - axes[2] * thickness / 2])
    return Piece(points, float(np.prod(np.maximum(_principal(points)[0], 1e-4))))


def _principal(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Extents along the principal axes (largest first) and the axes (rows; a third completes two)."""
    centred = points - points.mean(axis=0)
    _, vectors = np.linalg.eigh(centred.T @ centred)  # ascending: the largest spread last
    axes = vectors[:, ::-1].T
    projected = centred @ axes.T
    return projected.max(axis=0) - projected.min(axis=0), axes
