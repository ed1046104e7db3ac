"""The builder twin of ptu_camera.yaml: a video camera on a pan-tilt unit, looking at labelled objects."""
from morse.builder import *

robot = ATRV()

pose = Pose()
robot.append(pose)

motion = MotionVW()
robot.append(motion)

ptu = PTU()
ptu.translate(0.3, 0.0, 0.4)
ptu.properties(Speed=1.0)
robot.append(ptu)

# appended to the unit: both ride on its tilt body
camera = VideoCamera()
camera.translate(0.03, 0.0, 0.04)
ptu.append(camera)

posture = PTUPosture()
ptu.append(posture)

robot.add_default_interface('socket')

red_box = Cube()
red_box.size = [0.5, 0.5, 0.5]
red_box.translate(3.0, 1.5, 0.25)
red_box.color(0.8, 0.1, 0.1)
red_box.properties(Label='red_box', Object=True, Description='a red crate')

green_cylinder = Cylinder()
green_cylinder.size = [0.4, 0.4, 0.8]
green_cylinder.translate(2.0, -2.0, 0.4)
green_cylinder.color(0.1, 0.7, 0.2)
green_cylinder.properties(Label='green_cylinder', Object=True, Description='a green barrel')

blue_ball = Sphere()
blue_ball.size = [0.6, 0.6, 0.6]
blue_ball.translate(-1.0, 2.5, 0.3)
blue_ball.color(0.1, 0.3, 0.9)
blue_ball.properties(Label='blue_ball', Object=True, Description='a blue ball')

env = Environment('empty')
env.set_camera_location([-2.0, 0.3, 1.5])
env.set_camera_rotation([1.2, 0.0, -1.6])
