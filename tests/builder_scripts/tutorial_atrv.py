""" MORSE's quick tutorial (doc/morse/user/tutorial.rst): an ATRV with a v-omega motion controller
and a pose sensor, every component on the socket interface. """

from morse.builder import *

# Append ATRV robot to the scene
robot = ATRV()

# Append an actuator
motion = MotionVW()
robot.append(motion)

# Append a sensor
pose = Pose()
pose.translate(z = 0.75)
robot.append(pose)

# Configure the robot on the 'socket' interface
robot.add_default_interface('socket')

env = Environment('empty')
env.set_camera_location([10.0, -10.0, 10.0])
env.set_camera_rotation([1.0470, 0, 0.7854])
