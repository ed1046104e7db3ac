"""The one walk over a scene's component tree: every sensor and actuator, parents before children."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any, NamedTuple

from morsec.scene.naming import join


class Placed(NamedTuple):
    robot: Any  # the robot it is mounted on
    component: Any  # the IR component
    fqn: str  # robot.child.grandchild
    parent: str  # the fqn of what it is mounted on (the robot's name for a direct child)
    path: tuple  # where it is in the scene: ("robots", 0, "components", 1, ...)


def walk_components(scene) -> Iterator[Placed]:
    for r, robot in enumerate(scene.robots):
        yield from walk_children(robot, robot.components, robot.name, ("robots", r))


def walk_children(robot, components, parent: str, path: tuple) -> Iterator[Placed]:
    for i, comp in enumerate(components):
        fqn = join(parent, comp.name)
        here = path + ("components", i)
        yield Placed(robot, comp, fqn, parent, here)
        yield from walk_children(robot, comp.components, fqn, here)
