""" MORSE's multinode socket tutorial (docs/multinode.md): two equipped ATRVs in LAAS's robotics hall, dala1
simulated by the node named nodeA, dala2 by nodeB. Run the same script on each node:

    morsec multinode-server
    MORSE_NODE=nodeA morsec run tutorial-socket.py
    MORSE_NODE=nodeB morsec run tutorial-socket.py
"""

from dala_simple import equipped_robot  # beside this script: its folder is on sys.path

from morse.builder import *

dala1 = equipped_robot('socket')
dala2 = equipped_robot('socket')
dala2.translate(5, -3, 0)

env = Environment('laas/grande_salle')
env.show_framerate(True)
env.show_physics(False)

env.configure_multinode(protocol='socket', distribution={
    'nodeA': [dala1.name],
    'nodeB': [dala2.name],
})
# on several machines: server_address='<the server machine>', server_port='65000' (and run the server with
# `morsec multinode-server --bind 0.0.0.0`)

env.set_camera_rotation([1.3300, 0, 0.7854])
env.set_camera_location([10.0, -10.0, 3.0])

env.create()
