""" Middleware bindings: by name, with keyword arguments, and as full MORSE binding lists. """

from morse.builder import *

robot = ATRV()

pose = Pose()
pose.add_stream('socket', port = 60500)
pose.add_stream('text', file = 'pose.txt')
robot.append(pose)

odometry = Odometry()
odometry.configure_mw(['morse.middleware.socket_datastream.SocketDatastreamManager', 'publish',
                       'morse/middleware/socket_datastream'])
robot.append(odometry)

motion = MotionVW()
motion.add_interface('socket')
robot.append(motion)

teleport = Teleport()
teleport.add_stream('socket')
teleport.configure_service('socket')
robot.append(teleport)

env = Environment('empty')
env.configure_service('socket')
env.configure_stream_manager('socket', time_sync = True, sync_port = 12000)
