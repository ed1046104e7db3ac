"""MORSE's `tfMessage` (its copy of tf/tfMessage, for /tf without the tf package): tf2_msgs' TFMessage, the
same definition (and md5sum) under its ROS 1 name."""

from morse.testing.ros import RosInstallationError
from morsec.errors import MorsecError
from morsec.middleware.ros.available import require_ros

try:
    require_ros("morse.middleware.ros.tfMessage")
except MorsecError as _err:
    raise RosInstallationError(_err.message) from None

from tf2_msgs.msg import TFMessage as tfMessage  # noqa: E402

__all__ = ["tfMessage"]
