""" Robot settings: mass, friction, ghost, collision, physics type, colour. """

from morse.builder import *

heavy = ATRV()
heavy.set_mass(120.0)
heavy.set_friction(0.8)
heavy.set_color(0.2, 0.2, 0.8)

ghost = ATRV()
ghost.translate(x = 3.0)
ghost.make_ghost(alpha = 0.4)

statue = ATRV()
statue.translate(x = -3.0)
statue.set_physics_type('STATIC')

phantom = ATRV()
phantom.translate(y = 3.0)
phantom.set_no_collision()

rigid = ATRV()
rigid.translate(y = -3.0)
rigid.set_rigid_body()

for robot in (heavy, ghost, statue, phantom, rigid):
    pose = Pose()
    robot.append(pose)
    robot.add_default_interface('socket')

env = Environment('empty')
env.create()
