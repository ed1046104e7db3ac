""" properties, levels of realism and frequencies, as MORSE's sensor tests set them. """

from morse.builder import *

robot = ATRV()
robot.properties(NoGravity = False)

motion = MotionVW()
motion.properties(ControlType = 'Position')
motion.frequency(30)
robot.append(motion)

raw = Odometry()
raw.level('raw')
raw.frequency(10)
raw.add_stream('socket')
robot.append(raw)

diff = Odometry()
diff.level('differential')
diff.add_stream('socket')
robot.append(diff)

integ = Odometry()
integ.level('integrated')
integ.frequency(120)
integ.add_stream('socket')
integ.profile()
robot.append(integ)

pose = Pose()
pose.frequency(frequency = 5)
pose.add_stream('socket')
robot.append(pose)

env = Environment('empty', fastmode = True)
env.properties(longitude = 1.26, latitude = 43.26, altitude = 130.0)
