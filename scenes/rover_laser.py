"""The builder twin of rover_laser.yaml."""
from morse.builder import *

rover = ATRV()

pose = Pose()
pose.translate(z=-0.1)
rover.append(pose)

odometry = Odometry()
rover.append(odometry)

sick = Sick()
sick.translate(0.5, 0.0, 0.4)
rover.append(sick)

waypoint = Waypoint()
rover.append(waypoint)

rover.add_default_interface('socket')

env = Environment('indoors-1/boxes')
env.set_camera_location([-2.0, -14.0, 9.0])
env.set_camera_rotation([0.95, 0.0, 0.0])
