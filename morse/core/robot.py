"""MORSE's `morse.core.robot.Robot`: what a component's `self.robot_parent` is (morse.core.emulation's robot:
`bge_object`, `position_3d`, `name()`, `gettime()`, `apply_speed`, `force_pose`). Robots themselves are
morsec's catalogue robots: a MORSE robot class (a `.blend` model with its Python class) is not emulated."""

from morse.core.emulation import RobotParent as Robot

__all__ = ["Robot"]
