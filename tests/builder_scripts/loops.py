""" Several robots created in loops, the two ways MORSE's documentation describes (an explicit name, or
AbstractComponent.close_context()) and the plain way (morsec names them like the first two). """

from math import pi

from morse.builder import *

# explicit name in a loop: explorer, explorer_001, explorer_002
for i in range(3):
    robot = ATRV('explorer')
    robot.translate(x = 2.0 * i)
    motion = MotionVW()
    motion.add_interface('socket')
    robot.append(motion)

# close_context, as the flocking example
for i in range(1, 4):
    flock = ATRV()
    AbstractComponent.close_context()
    pose = Pose()
    pose.frequency(2)
    pose.add_interface('socket')
    flock.append(pose)
    flock.translate(x = -3.0 * i, y = 2.0)
    flock.rotate(z = pi / 4 * i)
    flock.add_default_interface('socket')

# no help at all: the variable name, suffixed
for i in range(2):
    scout = ATRV()
    scout.translate(y = -4.0 - i)

# a robot from a list comprehension has no variable: it is named after its type
others = [ATRV() for i in range(2)]
for n in range(2):
    others[n].translate(x = 10.0 + n)

env = Environment('empty', fastmode = True)
env.create()
