"""MORSE's `morse.middleware.ros`: the names MORSE's ROS test files import (`tfMessage`). The serialisers
MORSE scripts name (`morse.middleware.ros.pose.PoseStampedPublisher` ...) are class paths morsec's ROS
middleware reads from the scene (docs/ros.md), not modules to import."""
