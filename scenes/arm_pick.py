"""The builder twin of arm_pick.yaml: a KUKA LWR with a gripper on an ATRV, next to a Graspable box."""
from morse.builder import *

robot = ATRV()

pose = Pose()
robot.append(pose)

motion = MotionVW()
robot.append(motion)

arm = KukaLWR()
arm.translate(0.25, 0.0, 0.4)
robot.append(arm)

# appended to the arm: placed in the arm's frame (straight up), at its tip, and carried by its last link
gripper = Gripper()
gripper.translate(0.0, 0.0, 1.3105)
gripper.rotate(0.0, -1.5708, 0.0)
arm.append(gripper)

pose = ArmaturePose()
arm.append(pose)

robot.add_default_interface('socket')

table = Cube()
table.size = [0.5, 0.8, 0.4]
table.translate(1.0, 0.0, 0.2)
table.color(0.55, 0.4, 0.25)

box = Cube()
box.size = [0.06, 0.06, 0.06]
box.translate(0.9, 0.0, 0.43)
box.color(0.1, 0.4, 0.9)
box.set_dynamic()
box.set_mass(0.2)
box.properties(Label='box', Object=True, Graspable=True)

env = Environment('empty')
env.set_camera_location([-0.2, -2.6, 1.6])
env.set_camera_rotation([1.3, 0.0, -0.2])
