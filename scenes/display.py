"""The builder twin of display.yaml: MORSE's display settings.

    morsec render scenes/display.py -o display.png
    morsec run scenes/display.py --view native      # on a desktop; Ctrl+C stops it
"""
from morse.builder import *

robot = ATRV()

pose = Pose()
pose.add_stream('socket')
robot.append(pose)

motion = MotionVW()
motion.add_stream('socket')
robot.append(motion)

env = Environment('sandbox')
env.place_camera([4.0, -4.0, 2.5])
env.aim_camera([1.1, 0.0, 0.7854])
env.show_framerate(True)
env.show_physics(True)
env.show_debug_properties(True)
env.set_viewport('WIREFRAME')
env.set_auto_start(False)
env.fullscreen(True)
env.create()
