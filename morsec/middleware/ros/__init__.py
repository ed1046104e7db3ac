"""MORSE's ROS (1) middleware: a topic per stream with MORSE's names and message types, services adapted by
overlays (ROS actions), /clock in simulated time and tf. rospy is imported only when a simulation uses it
(`Ros.__init__`); building a scene asks `available` whether ROS is installed, without importing it."""

from morsec.middleware.ros.middleware import Ros

__all__ = ["Ros"]
