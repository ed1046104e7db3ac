"""The ROS rover of ros_rover.yaml as a MORSE builder script (docs/ros.md), with MORSE's ROS idioms: a
serialiser named by MORSE's class path, a topic of one's own, the pose as a tf transform."""
from morse.builder import *

rover = ATRV()

pose = Pose()
pose.add_stream('ros', 'morse.middleware.ros.pose.PoseStampedPublisher')   # /rover/pose, in /map
pose.add_stream('ros', method='morse.middleware.ros.pose.TFPublisher')    # /map -> /base_link on /tf
rover.append(pose)

odometry = Odometry()
odometry.add_stream('ros')                                                  # /rover/odometry
rover.append(odometry)

motion = MotionVW()
motion.add_stream('ros', topic='/cmd_vel')                                  # geometry_msgs/Twist in
rover.append(motion)

sick = Sick()
sick.translate(x=0.5, z=0.3)
sick.add_stream('ros')                                                      # /rover/sick
rover.append(sick)

env = Environment('indoors-1/boxes')
