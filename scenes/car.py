"""The builder twin of car.yaml."""
from morse.builder import *

car = Hummer()

pose = Pose()
car.append(pose)

steer_force = SteerForce()
car.append(steer_force)

car.add_default_interface('socket')

env = Environment('empty')
env.set_camera_location([-8.0, -8.0, 5.0])
env.set_camera_rotation([1.1, 0.0, -0.7854])
