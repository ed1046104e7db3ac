""" Modifiers: noise, NED, UTM and friends (alter by name or by MORSE classpath). """

from morse.builder import *

robot = ATRV()

pose = Pose()
pose.alter('Noise', pos_std = 0.1, rot_std = 0.05)
pose.add_stream('socket')
robot.append(pose)

ned_pose = Pose()
ned_pose.alter('NED')
ned_pose.add_stream('socket')
robot.append(ned_pose)

utm_pose = Pose()
utm_pose.alter('UTM', x_offset = 100.0, y_offset = -50.0)
utm_pose.add_stream('socket')
robot.append(utm_pose)

odometry = Odometry()
odometry.alter(classpath = 'morse.modifiers.odometry_noise.OdometryNoiseModifier', factor = 1.05)
odometry.add_stream('socket')
robot.append(odometry)

teleport = Teleport()
teleport.alter('NED')
teleport.add_stream('socket')
robot.append(teleport)

env = Environment('empty')
env.properties(longitude = 43.6, latitude = 1.4333, altitude = 135.0, UTMXOffset = 10.0)
env.set_random_seed(42)
