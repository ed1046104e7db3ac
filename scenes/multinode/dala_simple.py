""" The robot of the multinode tutorial: an ATRV with (v, w) motion, a pose sensor, a SICK laser and a small
video camera, every component on the middleware `mw`. """

from morse.builder import *


def equipped_robot(mw='socket'):
    atrv = ATRV()

    motion = MotionVW()
    atrv.append(motion)

    pose = Pose()
    pose.translate(x=0.2, z=0.83)
    atrv.append(pose)

    sick = Sick()
    sick.translate(x=0.18, z=0.94)
    sick.properties(resolution=1, laser_range=5.0)
    atrv.append(sick)

    cam = VideoCamera()
    cam.translate(x=0.3, z=1.1)
    cam.properties(cam_width=128, cam_height=128)
    atrv.append(cam)

    for component in (motion, pose, sick, cam):
        component.add_stream(mw)
    return atrv
