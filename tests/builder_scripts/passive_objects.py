""" Passive objects (basic meshes) and zones: MORSE's Cube/Cylinder/Sphere span -1..1 at scale 1, and a
Zone's size is its half-extent, so sizes are twice the scale. """

from morse.builder import *

table = Cube()
table.scale = (1.0, 0.5, 0.4)
table.translate(x = 3.0, z = 0.4)
table.color(0.6, 0.4, 0.2)
table.properties(Object = True, Label = 'table', Type = 'Furniture')

bottle = Cylinder('bottle')
bottle.scale = (0.04, 0.04, 0.12)
bottle.translate(x = 3.0, z = 0.92)
bottle.setgraspable()

ball = Sphere()
ball.scale = [0.1, 0.1, 0.1]
ball.translate(x = -2.0, z = 0.1)
ball.set_color(1.0, 0.0, 0.0)
ball.set_dynamic()
ball.set_mass(0.5)

charging_zone = Zone(type = 'Charging')
charging_zone.size = [2.0, 2.0, 1.0]
charging_zone.translate(x = 5.0, y = 5.0)

danger = Zone(type = 'Danger')
danger.properties(Level = 3)
danger.translate(x = -5.0)

robot = ATRV()
robot.append(Pose())

env = Environment('empty')
