"""The builder twin of foxglove_rover.yaml: a rover to watch in Foxglove (docs/foxglove.md)."""
from morse.builder import *

rover = ATRV()

pose = Pose()
pose.translate(z=-0.1)
rover.append(pose)

odometry = Odometry()
rover.append(odometry)

motion = MotionVW()
rover.append(motion)

sick = Sick()
sick.translate(0.5, 0.0, 0.4)
rover.append(sick)

camera = VideoCamera()
camera.translate(0.6, 0.0, 0.6)
camera.properties(cam_width=160, cam_height=120)
rover.append(camera)

depth = DepthCamera()
depth.translate(0.6, 0.0, 0.7)
depth.properties(cam_width=80, cam_height=60, cam_far=20.0)
rover.append(depth)

rover.add_default_interface('socket')

env = Environment('indoors-1/boxes')
env.set_camera_location([-2.0, -14.0, 9.0])
env.set_camera_rotation([0.95, 0.0, 0.0])
