"""The builder twin of quadrotor_waypoints.yaml."""
from morse.builder import *

quadrotor = Quadrotor()

pose = Pose()
quadrotor.append(pose)

imu = IMU()
quadrotor.append(imu)

gps = GPS()
gps.level('raw')
quadrotor.append(gps)

waypoint = RotorcraftWaypoint()
quadrotor.append(waypoint)

quadrotor.add_default_interface('socket')

env = Environment('sandbox')
env.properties(longitude=1.4437, latitude=43.6045, altitude=146.0)
env.set_camera_location([8.0, -8.0, 6.0])
env.set_camera_rotation([1.0, 0.0, 0.7854])
