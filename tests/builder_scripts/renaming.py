#! /usr/bin/env morseexec
""" Renaming, as MORSE's testing/base/renaming_testing.py: components are named after the builder
script's variables (or an explicit name), robots created in a loop get _001, _002 ... suffixes.

The KUKA arm of the original is a Teleport actuator here, with a Pose sensor appended to it.
"""

from morse.builder import *


class MyATRV(ATRV):
    def __init__(self, name=None):
        ATRV.__init__(self, name)
        self.arm = Teleport()
        self.append(self.arm)
        self.pose = Pose()
        self.arm.append(self.pose)

morsy = ATRV()
arm = Teleport()
arm.name = 'my_kuka'
morsy.append(arm)
pose = Pose('my_pose')
arm.append(pose)

robot2 = ATRV('mana')
arm = Teleport()
robot2.append(arm)
pose = Pose()
pose.name = 'my_pose2'
arm.append(pose)

robot3 = ATRV()
robot3.name = 'dala'
arm = Teleport('my_kuka')
robot3.append(arm)
pose = Pose()
arm.append(pose)

robot4 = MyATRV()
robot5 = MyATRV('foo')
robot6 = MyATRV()
robot6.name = 'bar'

for i in range(10):
    m = ATRV()
    arm = Teleport()
    m.append(arm)
    pose = Pose()
    arm.append(pose)
    AbstractComponent.close_context()

for i in range(3):
    robot = ATRV()
    robot.translate(x=i)

for i in range(2):
    r = ATRV('named')

env = Environment('empty', fastmode=True)
env.create()
