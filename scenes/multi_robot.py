"""The builder twin of multi_robot.yaml: several robots in the sandbox.

Robots and components are named after the variables that hold them, as in MORSE; a variable used for
a second robot gives it a suffix (the two ATRVs below are `atrv` and `atrv_001`), and an object held by
no variable is named after its type (the zone below is `Charging`).
"""
from morse.builder import *

# the first ATRV: a socket stream + service on each of its components
atrv = ATRV()
atrv.translate(x=-2.0)
atrv.add_default_interface('socket')
pose = Pose()
atrv.append(pose)
motion_vw = MotionVW()
atrv.append(motion_vw)
odo = Odometry()
odo.level('integrated')
odo.frequency(30)
atrv.append(odo)

# the second ATRV, in the same variable: atrv_001
atrv = ATRV()
atrv.translate(x=-2.0, y=-2.0)
atrv.rotate(z=1.5708)
pose = Pose()
pose.add_stream('socket')
atrv.append(pose)
motion_vw = MotionVW()
motion_vw.add_stream('socket')
motion_vw.add_service('socket')
atrv.append(motion_vw)
odometry = Odometry()
odometry.level('differential')
odometry.add_stream('socket')
atrv.append(odometry)

pioneer3dx = Pioneer3DX()
pioneer3dx.translate(x=2.0, y=1.5)
pioneer3dx.rotate(z=3.1416)
pioneer3dx.properties(FixTurningSpeed=0.52)
pose = Pose()
pose.add_stream('socket')
pioneer3dx.append(pose)
motion = MotionVW()
motion.add_stream('socket')
motion.add_service('socket')
pioneer3dx.append(motion)
odo = Odometry()
odo.add_stream('socket', port=60200)
pioneer3dx.append(odo)

heli = RMax()                    # floats: NoGravity is true by default
heli.translate(z=3.0, y=5.0)
pose = Pose()
pose.add_stream('socket')
heli.append(pose)
teleport = Teleport()
teleport.add_stream('socket')
teleport.add_service('socket')
heli.append(teleport)

watcher = FakeRobot()            # a fixed pose reference, on no robot
watcher.translate(y=-8.0, z=2.0)
pose = Pose()
pose.add_stream('socket')
watcher.append(pose)

# MORSE's basic meshes span -1..1 at scale 1: scale 0.25 gives a 0.5 m crate
crate = Cube()
crate.scale = (0.25, 0.25, 0.25)
crate.translate(2.0, -2.0, 0.25)
crate.color(0.7, 0.5, 0.2)
crate.set_dynamic()
crate.set_mass(5.0)
crate.properties(Label='crate', Object=True, Graspable=True)

barrel = Cylinder()
barrel.scale = (0.25, 0.25, 0.4)
barrel.translate(-1.0, 3.0, 0.4)
barrel.color(0.2, 0.4, 0.8)
barrel.properties(Label='barrel', Object=True)

# a Zone is a unit cube (half-extent 1, so 2 m wide); held by no variable, it is named after its type
Zone(type='Charging').translate(7.0, 7.0, 1.0)

env = Environment('sandbox')
env.set_time_strategy(TimeStrategies.FixedSimulationStep)
env.set_camera_location([12.0, -12.0, 9.0])
env.set_camera_rotation([0.95, 0.0, 0.7854])
env.add_service('socket')
env.create()
