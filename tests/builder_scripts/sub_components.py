""" append on sub-components: a Pose sensor carried by a Teleport actuator carried by the robot, and
a class describing a robot, as MORSE's renaming test does. """

from morse.builder import *


class Carrier(ATRV):
    def __init__(self, name = None):
        ATRV.__init__(self, name)
        self.platform = Teleport()
        self.platform.translate(z = 0.3)
        self.append(self.platform)
        self.platform_pose = Pose()
        self.platform.append(self.platform_pose)
        self.odometry = Odometry()
        self.append(self.odometry)

carrier = Carrier()
carrier.add_default_interface('socket')

worker = Carrier('worker')
worker.translate(x = 3.0)

# a deeper tree, built bottom-up
tip = Pose()
tip.translate(z = 0.1)
mount = Teleport()
mount.append(tip)
base_pose = Pose()
base_pose.append(mount)
lifter = ATRV()
lifter.translate(y = 3.0)
lifter.append(base_pose)

env = Environment('empty')
