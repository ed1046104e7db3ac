""" Multinode configuration (doc/morse/user/multinode): two robots, one per node. """

from morse.builder import *

dala1 = ATRV()
pose1 = Pose()
pose1.add_stream('socket')
dala1.append(pose1)

dala2 = ATRV()
dala2.translate(x = 2.0)
pose2 = Pose()
pose2.add_stream('socket')
dala2.append(pose2)

env = Environment('empty')
env.configure_multinode(protocol = 'socket',
                        server_address = 'localhost',
                        server_port = '65000',
                        distribution = {
                            "nodeA": [dala1.name],
                            "nodeB": [dala2.name],
                        })
env.create()
