""" Display settings and Blender-only calls: accepted, the Blender-only ones recorded and warned about. """

from morse.builder import *

robot = ATRV()
pose = Pose()
pose.add_stream('socket')
robot.append(pose)

env = Environment('empty')
env.show_framerate(True)
env.show_physics(True)
env.show_debug_properties(True)
env.set_viewport(viewport_shade = 'SOLID', clip_end = 500)
env.set_auto_start(True)
env.place_camera([5.0, -5.0, 6.0])
env.aim_camera([1.0470, 0, 0.7854])
env.set_camera_clip(clip_start = 0.5, clip_end = 200)
env.set_camera_focal_length(35.0)
env.set_camera_speed(4.0)
env.set_debug(False)
env.set_material_mode('GLSL')
env.set_horizon_color(color = (0.1, 0.2, 0.3))
env.enable_mist(True)
env.use_vsync('OFF')
env.set_stereo(stereo = 'NONE')
env.create()
