"""The builder twin of tutorial.yaml: the same scene written as a MORSE builder script.

    morsec build scenes/tutorial.py        # byte-identical to `morsec build scenes/tutorial.yaml`
    python scenes/tutorial.py              # the same, as plain Python (with `from morsec.builder import *`)
"""
from morse.builder import *

# an ATRV named 'robot' after its variable, with a socket stream + service on every component lacking one
robot = ATRV()
robot.add_default_interface('socket')

pose = Pose()
pose.translate(z=-0.10)          # at ground level: the ATRV's origin is 0.10 m up
pose.add_stream('socket')
robot.append(pose)

motion = MotionVW()
motion.add_service('socket')
robot.append(motion)

odo = Odometry()
odo.level('differential')
odo.frequency(30)
odo.add_stream('socket', port=60100)
robot.append(odo)

# a 0.5 m crate: MORSE's Cube is 2 m wide at scale 1 (it spans -1..1), so scale 0.25
crate = Cube()
crate.scale = (0.25, 0.25, 0.25)
crate.translate(3.0, 1.0, 0.25)
crate.properties(Label='crate', Object=True)

# a charging zone; MORSE's Zone.size is the half-extent: 2.5 -> a 5 m cube
charging = Zone(type='Charging')
charging.name = 'Charging'       # the YAML twin leaves the zone unnamed: its name is its type
charging.size = [2.5, 2.5, 2.5]
charging.translate(10.0, 0.0, 2.0)

env = Environment('empty')
env.set_gravity(9.81)
env.set_time_strategy(TimeStrategies.BestEffort)
env.set_camera_location([10.0, -10.0, 3.0])
env.set_camera_rotation([1.33, 0.0, 0.7854])
env.properties(longitude=43.6, latitude=1.4333, altitude=135.0)
env.add_service('socket')
env.create()
